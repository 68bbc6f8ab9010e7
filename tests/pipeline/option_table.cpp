#include "option_table.hpp"

#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogrsf_frmts.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>

#include "core/content_hash.hpp"
#include "test_support.hpp"

namespace tw::test {

namespace fs = std::filesystem;
using nlohmann::json;

std::vector<std::string> words(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string w; in >> w;) {
    for (char& c : w)
      if (c == '~') c = ' ';
    out.push_back(w);
  }
  return out;
}

namespace {

std::string quoted(const std::string& word) {
  std::string q = "'";  // a shell word: ' as '\''
  for (char ch : word) q += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return q + "'";
}

// What `terraweave COMMAND --help` prints for each command, in children forked from one process.
std::map<std::string, std::string> help_texts(const std::set<std::string>& commands) {
  TempDir logs;
  const fs::path list = logs / "help.txt";
  {
    std::ofstream batch(list);
    int k = 0;
    for (const std::string& command : commands) {
      batch << logs.path().string() << '\t' << (logs / (std::to_string(k) + ".out")).string()
            << '\t' << (logs / (std::to_string(k) + ".err")).string() << '\t';
      for (const std::string& word : words(command)) batch << word << '\t';
      batch << "--help\t\n";
      ++k;
    }
  }
  EXPECT_EQ(std::system(("TERRAWEAVE_FORK_BATCH=" + quoted(list.string()) + " " +
                         quoted(terraweave_binary().string()))
                            .c_str()),
            0);
  std::map<std::string, std::string> texts;
  int k = 0;
  for (const std::string& command : commands) {
    const std::string text = read_file(logs / (std::to_string(k++) + ".out"));
    EXPECT_NE(text.find("Usage:"), std::string::npos) << command << " --help";
    // The command's own part: the global options follow in a subcommand's footer.
    texts[command] = text.substr(0, text.find("Global options"));
  }
  return texts;
}

std::string help_text(const std::string& command) {
  return help_texts({command})[command];
}

// The first words of the lines of a CLI11 help section ("Options:", "Positionals:", ...).
std::vector<std::string> section_entries(const std::string& help, const std::string& section) {
  std::vector<std::string> entries;
  bool inside = false;
  for (const std::string& line : lines_of(help)) {
    if (!line.empty() && line[0] != ' ') {
      inside = line == section;
      continue;
    }
    // An entry is indented by two spaces; its description's continuation by many more.
    if (!inside || line.size() < 3 || line[2] == ' ') continue;
    std::string entry = line.substr(2, line.find(' ', 2) - 2);
    entries.push_back(entry);
  }
  return entries;
}

std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  if (from.empty()) return text;
  for (std::size_t at = text.find(from); at != std::string::npos;
       at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

std::string substitute(const std::string& text, const fs::path& data_dir) {
  return replace_all(text, "@d", data_dir.string());
}

// A GeoPackage as text: every layer's features, fields and geometry.
std::string gpkg_text(const fs::path& path) {
  GDALAllRegister();
  std::unique_ptr<GDALDataset> ds(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY,
                                                    nullptr, nullptr, nullptr));
  if (!ds) return "(unreadable GeoPackage)";
  std::string text;
  for (OGRLayer* layer : ds->GetLayers()) {
    text += std::string("layer ") + layer->GetName() + "\n";
    for (auto& f : *layer) {
      for (int i = 0; i < f->GetFieldCount(); ++i)
        text += std::string(f->GetFieldAsString(i)) + ";";
      if (const OGRGeometry* g = f->GetGeometryRef()) text += g->exportToWkt();
      text += "\n";
    }
  }
  return text;
}

// Drops what changes from run to run of the same inputs (timings: "timings", "started_utc",
// "seconds", "plan_seconds", "growth_ms", ...) from a JSON document.
void drop_timings(json& j) {
  if (j.is_object()) {
    for (auto it = j.begin(); it != j.end();) {
      const std::string& key = it.key();
      if (key == "timings" || key == "started_utc" || key.ends_with("seconds") ||
          key.ends_with("_ms"))
        it = j.erase(it);
      else
        drop_timings(*it++);
    }
  } else if (j.is_array()) {
    for (json& item : j) drop_timings(item);
  }
}

std::string digest(const fs::path& file, const std::string& relative, const fs::path& work,
                   const fs::path& folder) {
  std::string content;
  if (file.extension() == ".gpkg") {
    content = gpkg_text(file);
  } else {
    content = read_file(file);
    if (file.extension() == ".json") {
      json j = json::parse(content, nullptr, false);
      if (!j.is_discarded()) {
        if (relative.ends_with("report.json") && j.is_object() && j.contains("outputs"))
          j = json{{"outputs", j["outputs"]}, {"warnings", j.value("warnings", json())}};
        drop_timings(j);
        content = j.dump();
      }
    }
  }
  content = replace_all(replace_all(content, folder.string(), "@o"), work.string(), "@w");
  return content_hash(content);
}

std::string normalized(std::string text, const fs::path& work, const fs::path& folder) {
  text = replace_all(replace_all(text, folder.string(), "@o"), work.string(), "@w");
  static const std::regex duration(R"(\b[0-9]+(\.[0-9]+)? (s|ms)\b)");
  return std::regex_replace(text, duration, "T $2");
}

}  // namespace

std::set<std::string> help_options(const std::string& command) {
  const std::string help = help_text(command);
  std::set<std::string> options;
  for (const char* section : {"Options:", "Positionals:"})
    for (const std::string& entry : section_entries(help, section)) {
      // -q,--quiet: --quiet; --no-stitch{false}: --no-stitch
      std::string name = entry.substr(entry.rfind(',') + 1);
      name = name.substr(0, name.find('{'));
      if (name != "--help") options.insert(name);
    }
  return options;
}

std::set<std::string> help_subcommands(const std::string& command) {
  const std::vector<std::string> entries = section_entries(help_text(command), "Subcommands:");
  return {entries.begin(), entries.end()};
}

std::set<std::string> leaf_commands() {
  const std::set<std::string> top = help_subcommands("");
  const std::map<std::string, std::string> texts = help_texts(top);
  std::set<std::string> leaves;
  for (const auto& [command, text] : texts) {
    const std::vector<std::string> subs = section_entries(text, "Subcommands:");
    if (subs.empty()) leaves.insert(command);
    for (const std::string& sub : subs) leaves.insert(command + " " + sub);
  }
  return leaves;
}

Batch::Batch(fs::path data_dir, fs::path work_root)
    : data_dir_(std::move(data_dir)), work_root_(std::move(work_root)) {}

const Outcome& Batch::operator[](const Invocation& invocation) const {
  return done_.at(invocation);
}

fs::path Batch::folder_of(const Invocation& invocation) const {
  return folders_.at(invocation);
}

void Batch::run(const std::vector<Invocation>& invocations) {
  std::vector<const Invocation*> todo;
  for (const Invocation& i : invocations)
    if (!done_.count(i) && std::find(todo.begin(), todo.end(), &i) == todo.end()) {
      bool seen = false;
      for (const Invocation* t : todo) seen = seen || *t == i;
      if (!seen) todo.push_back(&i);
    }
  if (todo.empty()) return;
  fs::create_directories(work_root_);
  const fs::path list = work_root_ / ("batch_" + std::to_string(done_.size()) + ".txt");
  std::vector<fs::path> works;
  {
    std::ofstream batch(list);
    for (const Invocation* i : todo) {
      const fs::path work = work_root_ / ("w" + std::to_string(done_.size() + works.size()));
      works.push_back(work);
      fs::create_directories(work);
      for (const auto& [name, text] : i->files) {
        fs::create_directories((work / name).parent_path());
        std::ofstream(work / name) << substitute(text, data_dir_);
      }
      auto line = [&](const std::vector<std::string>& args, const std::string& log) {
        batch << work.string() << '\t' << (work / (log + ".out")).string() << '\t'
              << (work / (log + ".err")).string() << '\t';
        for (const std::string& a : args) batch << substitute(a, data_dir_) << '\t';
        batch << '\n';
      };
      // Logs go beside the working folder (its name + .setupN / .run), not into it.
      for (std::size_t s = 0; s < i->setup.size(); ++s)
        line(i->setup[s], "../" + work.filename().string() + ".setup" + std::to_string(s));
      line(i->args, "../" + work.filename().string() + ".run");
    }
  }
  const std::string command =
      "TERRAWEAVE_FORK_BATCH=" + quoted(list.string()) + " " + quoted(terraweave_binary().string());
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  std::vector<int> statuses;
  std::istringstream status_text(read_file(fs::path(list.string() + ".status")));
  for (int st; status_text >> st;) statuses.push_back(st);
  std::size_t next_status = 0;
  for (std::size_t k = 0; k < todo.size(); ++k) {
    const Invocation& i = *todo[k];
    const fs::path work = works[k];
    const fs::path folder = i.folder.empty() ? work : work / i.folder;
    for (std::size_t s = 0; s < i.setup.size(); ++s) {
      const int st = next_status < statuses.size() ? statuses[next_status] : -1;
      ++next_status;
      EXPECT_TRUE(WIFEXITED(st) && WEXITSTATUS(st) == 0)
          << "setup " << s << " of " << work
          << " failed: " << read_file(work.string() + ".setup" + std::to_string(s) + ".err");
    }
    const int st = next_status < statuses.size() ? statuses[next_status++] : -1;
    Outcome o;
    o.exit_code = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    o.out = normalized(read_file(work.string() + ".run.out"), work, folder);
    o.err = normalized(read_file(work.string() + ".run.err"), work, folder);
    if (fs::is_directory(folder))
      for (const auto& entry : fs::recursive_directory_iterator(folder)) {
        if (!entry.is_regular_file()) continue;
        const std::string relative = fs::relative(entry.path(), folder).string();
        if (i.folder.empty() && i.files.count(relative)) continue;
        if (!i.ignore.empty() && relative.starts_with(i.ignore)) continue;
        // The output folder's lock and list of outputs name the writing process and its time.
        const std::string name = entry.path().filename().string();
        if ((entry.path().parent_path().filename() == ".terraweave" &&
             (name == "lock" || name == "outputs")) ||
            name == ".lock")
          continue;
        o.files[relative] = digest(entry.path(), relative, work, folder);
      }
    done_[i] = std::move(o);
    folders_[i] = work;
  }
}

namespace {

std::string collapse_spaces(const std::string& text) {
  std::string out;
  for (char c : text) {
    const bool space = c == ' ' || c == '\n' || c == '\t';
    if (space && (out.empty() || out.back() == ' ')) continue;
    out += space ? ' ' : c;
  }
  return out;
}

std::string differing_files(const Outcome& a, const Outcome& b) {
  std::string names;
  for (const auto& [name, hash] : a.files) {
    const auto other = b.files.find(name);
    if (other == b.files.end() || other->second != hash) names += " " + name;
  }
  for (const auto& [name, hash] : b.files)
    if (!a.files.count(name)) names += " " + name;
  return names;
}

}  // namespace

void check_option_rows(const std::string& table, const std::set<std::string>& listed,
                       const std::vector<OptionRow>& rows, Batch& batch) {
  std::set<std::string> tabled;
  for (const OptionRow& row : rows) tabled.insert(row.option);
  EXPECT_EQ(listed, tabled) << table << ": --help lists options the table does not, or the reverse";
  std::vector<Invocation> all;
  for (const OptionRow& row : rows) {
    if (row.expect == Expect::tested_by) continue;
    all.push_back(row.a);
    all.push_back(row.b);
  }
  batch.run(all);
  for (const OptionRow& row : rows) {
    if (row.expect == Expect::tested_by) {
      // "tests/pipeline/FILE.cpp: Suite.Test": the file defines that test (TEST or TEST_F).
      const std::size_t colon = row.doc.find(": ");
      ASSERT_NE(colon, std::string::npos) << table << " " << row.option << ": doc is FILE: TEST";
      const std::string test = row.doc.substr(colon + 2);
      const std::size_t dot = test.find('.');
      ASSERT_NE(dot, std::string::npos) << row.doc;
      const std::string text = read_file(source_dir() / row.doc.substr(0, colon));
      const std::string named = test.substr(0, dot) + ", " + test.substr(dot + 1) + ")";
      EXPECT_TRUE(text.find("TEST(" + named) != std::string::npos ||
                  text.find("TEST_F(" + named) != std::string::npos)
          << table << " " << row.option << ": " << row.doc.substr(0, colon) << " has no test "
          << test;
      std::printf("%-28s tested by %s\n", (table + " " + row.option).c_str(), test.c_str());
      continue;
    }
    const Outcome& a = batch[row.a];
    const Outcome& b = batch[row.b];
    const std::string where = table + " " + row.option;
    EXPECT_EQ(a.exit_code, row.a_exit) << where << " A: " << a.err;
    EXPECT_EQ(b.exit_code, row.b_exit) << where << " B: " << b.err;
    const std::string files = differing_files(a, b);
    const bool changed =
        a.exit_code != b.exit_code || a.out != b.out || a.err != b.err || !files.empty();
    switch (row.expect) {
      case Expect::changes:
        EXPECT_TRUE(changed) << where << ": B wrote and printed the same as A (ignored?)";
        break;
      case Expect::same_bytes:
        EXPECT_EQ(files, "") << where << ": documented to write the same bytes";
        break;
      case Expect::log_only:
        EXPECT_EQ(files, "") << where << ": documented to write the same bytes";
        EXPECT_NE(a.err, b.err) << where << ": documented to change the log";
        break;
      case Expect::tested_by:  // handled above: nothing was run
        break;
    }
    if (!row.doc.empty()) {
      const std::size_t colon = row.doc.find(": ");
      if (colon != std::string::npos) {
        const std::string text =
            collapse_spaces(read_file(source_dir() / row.doc.substr(0, colon)));
        EXPECT_NE(text.find(collapse_spaces(row.doc.substr(colon + 2))), std::string::npos)
            << where << ": " << row.doc.substr(0, colon) << " does not say '"
            << row.doc.substr(colon + 2) << "'";
      } else {
        ADD_FAILURE() << where << ": doc is FILE: SENTENCE";
      }
    } else {
      EXPECT_EQ(row.expect, Expect::changes)
          << where << ": a row expecting no change names its doc";
    }
    const char* what = row.expect == Expect::changes      ? "changes"
                       : row.expect == Expect::same_bytes ? "same bytes"
                                                          : "log only";
    std::printf("%-28s %-10s exit %d/%d%s%s%s%s\n", where.c_str(), what, a.exit_code, b.exit_code,
                a.out != b.out ? " stdout" : "", a.err != b.err ? " stderr" : "",
                files.empty() ? "" : " files:", files.substr(0, 120).c_str());
  }
}

}  // namespace tw::test
