#pragma once
// Issue #24 item 2: tables of A/B runs proving that every command line option and every pipeline
// key changes what terraweave writes or prints (or, where documented, that it does not). The
// machinery shared by tests/pipeline/option_tables_test.cpp and pipeline_keys_test.cpp: what
// `--help` lists, terraweave runs in children forked from one process (TERRAWEAVE_FORK_BATCH,
// src/cli/main.cpp: a spawn costs 0.2 s of loading libraries, a fork a millisecond), and a
// digest of what a run wrote that two runs compare by.
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace tw::test {

// The options `terraweave COMMAND --help` lists as the command's own (not the global ones in its
// footer): each by its long name (--quiet for -q,--quiet), positionals by their name; --help
// itself left out. COMMAND "" is the top level, "network clone" a nested subcommand.
std::set<std::string> help_options(const std::string& command);
// The subcommands `terraweave COMMAND --help` lists ("" is the top level).
std::set<std::string> help_subcommands(const std::string& command);
// Every command `terraweave --help` lists, a command with subcommands as "network clone", ...
std::set<std::string> leaf_commands();

// One terraweave invocation in a fresh working folder of its own: `files` are written there,
// then the `setup` command lines run, then `args` (the one measured). "@d" in an argument or a
// file stands for the table's data folder (absolute).
struct Invocation {
  std::vector<std::string> args;
  std::vector<std::vector<std::string>> setup = {};
  std::map<std::string, std::string> files = {};
  std::string folder = "";  // what is digested, relative to the working folder ("": all of it)
  std::string ignore = "";  // files of `folder` starting so are not (e.g. ".terraweave/")
  auto operator<=>(const Invocation&) const = default;
};

// What a measured invocation did. Paths of its working folder and digested folder read "@w" and
// "@o"; durations ("0.123 s", "12 ms") read "T".
struct Outcome {
  int exit_code = -1;
  std::string out, err;
  // Relative path -> content hash of every file in the folder but `files` (and but the output
  // folder's .terraweave/lock and .terraweave/outputs and a cache's .lock, which name the
  // writing process and the time); a JSON file without its timings (plan_seconds, ...), a
  // GeoPackage as the text of its features (its bytes carry a timestamp), report.json as its
  // `outputs` and `warnings` (the rest echoes the configuration and names the inputs).
  std::map<std::string, std::string> files;
};

// Runs invocations, each distinct one once, in children forked from one terraweave.
class Batch {
 public:
  explicit Batch(std::filesystem::path data_dir, std::filesystem::path work_root);
  const Outcome& operator[](const Invocation& invocation) const;
  // The working folder an invocation ran in (after run()).
  std::filesystem::path folder_of(const Invocation& invocation) const;
  void run(const std::vector<Invocation>& invocations);

 private:
  std::filesystem::path data_dir_, work_root_;
  std::map<Invocation, Outcome> done_;
  std::map<Invocation, std::filesystem::path> folders_;
};

// The words of a command line split at spaces; "~" in a word is a space ("--where a~=~1").
std::vector<std::string> words(const std::string& text);

enum class Expect {
  changes,     // exit status, stdout, stderr or a file differs
  same_bytes,  // every file is equal (what is printed may differ); documented
  log_only,    // every file is equal and the log (stderr) differs; documented
  // Takes effect only in a process that keeps running (the drawing server of `view --serve`):
  // the row runs nothing here, its doc names the test that changes it and checks the change.
  tested_by,
};

// One row: `option` changed from A to B. A `doc` is "docs/FILE.md: a sentence of that file"
// (whitespace-insensitive) that says why the bytes stay the same; rows that expect a change may
// give one too.
struct OptionRow {
  std::string option;
  Invocation a, b;
  Expect expect = Expect::changes;
  std::string doc = "";
  int a_exit = 0, b_exit = 0;  // the expected exit statuses
};

// Checks that `rows` name exactly `listed` (an option added without a row fails here), runs every
// row's A and B in `batch`, checks each against its expectation and prints one line per row.
void check_option_rows(const std::string& table, const std::set<std::string>& listed,
                       const std::vector<OptionRow>& rows, Batch& batch);

}  // namespace tw::test
