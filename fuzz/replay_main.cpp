// A fuzz target without libFuzzer: every file of its seed corpus, then a fixed number of
// deterministic mutations of each (truncations, flipped and inserted bytes, a non-UTF-8 byte,
// an out-of-range number, a repeated or deleted slice), through the same
// LLVMFuzzerTestOneInput. CI builds these with the normal compiler and runs them as tests
// (fuzz.<target>), so the harnesses and their corpus cannot rot and every mutation class the
// issue named is tried on every change; scripts/fuzz.sh builds the same files with clang and
// libFuzzer for open-ended, coverage-guided runs. A finding aborts (or escapes as an exception
// other than tw::Error, which terminates): the test fails, naming the input that did it.
//   fuzz_replay_<target> CORPUS_DIR [MUTATIONS_PER_FILE]
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);
extern "C" __attribute__((weak)) int LLVMFuzzerInitialize(int* argc, char*** argv);

namespace {

std::string read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// One mutation of `bytes`, chosen and placed by `random`.
std::string mutate(std::string bytes, std::mt19937_64& random) {
  const auto at = [&](std::size_t n) { return n == 0 ? 0 : std::size_t(random() % n); };
  switch (random() % 7) {
    case 0:  // truncated
      bytes.resize(at(bytes.size() + 1));
      break;
    case 1:  // a flipped bit
      if (!bytes.empty()) bytes[at(bytes.size())] ^= char(1u << (random() % 8));
      break;
    case 2:  // a byte that is not UTF-8
      bytes.insert(at(bytes.size() + 1), 1, char(0xE9));
      break;
    case 3: {  // a number out of every range
      const std::size_t digit = bytes.find_first_of("0123456789", at(bytes.size() + 1));
      if (digit != std::string::npos) bytes.replace(digit, 1, "1e400");
      break;
    }
    case 4: {  // a slice repeated
      const std::size_t from = at(bytes.size() + 1);
      const std::size_t length = at(std::min<std::size_t>(bytes.size() - from, 64) + 1);
      bytes.insert(from, bytes.substr(from, length));
      break;
    }
    case 5: {  // a slice deleted
      const std::size_t from = at(bytes.size() + 1);
      bytes.erase(from, at(std::min<std::size_t>(bytes.size() - from, 64) + 1));
      break;
    }
    default:  // a random byte
      if (!bytes.empty()) bytes[at(bytes.size())] = char(random() & 0xFF);
  }
  return bytes;
}

// The input being tried, kept where a finding (abort) writes it to replay-finding.bin in the
// working folder, so it can be run again under a debugger or by scripts/fuzz.sh.
const std::string* current_input = nullptr;

extern "C" void save_finding(int signal) {
  if (current_input) {
    const int fd = ::open("replay-finding.bin", O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      [[maybe_unused]] const auto n = ::write(fd, current_input->data(), current_input->size());
      ::close(fd);
    }
  }
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

void run_one(const std::string& bytes) {
  current_input = &bytes;
  LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
  current_input = nullptr;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s CORPUS_DIR [MUTATIONS_PER_FILE]\n", argv[0]);
    return 2;
  }
  if (LLVMFuzzerInitialize) LLVMFuzzerInitialize(&argc, &argv);
  for (const int signal : {SIGABRT, SIGSEGV, SIGFPE, SIGBUS}) std::signal(signal, save_finding);
  const int mutations = argc > 2 ? std::atoi(argv[2]) : 100;
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(argv[1]))
    if (entry.is_regular_file()) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  if (files.empty()) {
    std::fprintf(stderr, "%s: no corpus files\n", argv[1]);
    return 1;
  }
  long executions = 0;
  for (const auto& file : files) {
    const std::string seed = read_bytes(file);
    // Seeded by the file's name: the same mutations on every machine and every run.
    std::mt19937_64 random(std::hash<std::string>{}(file.filename().string()));
    std::fprintf(stderr, "replay: %s\n", file.filename().c_str());
    run_one(seed);
    ++executions;
    std::string current = seed;
    for (int i = 0; i < mutations; ++i) {
      // Mostly one mutation of the seed, sometimes a further one of the last input.
      current = mutate(random() % 4 == 0 ? current : seed, random);
      run_one(current);
      ++executions;
    }
  }
  std::printf("%zu corpus files, %ld executions, no finding\n", files.size(), executions);
  return 0;
}
