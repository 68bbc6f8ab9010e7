#pragma once
// Edits of a test's output files behind the program's back (the cache's guards against them).
#include <cstdint>
#include <filesystem>

namespace tw::test {

// Flips one byte of `path` in place, `from_end` bytes before its end (made writable first): an
// edit that keeps the file's size and inode, as an edit through a hard-linked output would.
// Fails the calling test when the file cannot be written.
void flip_byte_in_place(const std::filesystem::path& path, std::uintmax_t from_end);

}  // namespace tw::test
