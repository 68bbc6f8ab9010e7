#pragma once
// Whole small files as bytes. write_file_atomic writes a temporary beside the file (its name
// holds the host and pid, so processes on machines sharing a folder never share one) and
// renames it over `path`: a reader sees the old file or the new one, and a writer killed on the
// way leaves only its temporary.
#include <filesystem>
#include <string>
#include <string_view>

namespace tw {

// Throws tw::Error naming the file when it cannot be read.
std::string read_file_bytes(const std::filesystem::path& path);
// Creates the folder. Throws tw::Error naming the file when it cannot be written.
void write_file_atomic(const std::filesystem::path& path, std::string_view bytes);
// A name for a temporary beside `path`: .<stem>.tmp-<host>-<pid><ext> (same extension, for
// writers that look at it).
std::filesystem::path temporary_beside(const std::filesystem::path& path);

}  // namespace tw
