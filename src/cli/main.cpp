// Placeholder until the pipeline lands; replaced by the CLI (issue #2).
#include <cstdio>
int main() { std::puts("terraweave"); return 0; }
