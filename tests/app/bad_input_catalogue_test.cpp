// Walks the bad-input catalogue of docs/extreme-cases.md: every row's command gets exit code 2
// and exactly one `ddish: error:` line, the last line of stderr, equal to the row's line (up to
// the `…` where a row ends in one).
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cli_runner.h"

namespace {

namespace fs = std::filesystem;

struct Row {
  int number = 0;
  std::string args;  // after "ddish "
  std::string line;  // expected
};

// The cells of a markdown table row, split at '|' not escaped as "\|", unescaped and trimmed.
std::vector<std::string> cells(const std::string& row) {
  std::vector<std::string> out;
  std::string cur;
  for (std::size_t i = 1; i < row.size(); ++i) {
    if (row[i] == '\\' && i + 1 < row.size() && row[i + 1] == '|') {
      cur += '|';
      ++i;
    } else if (row[i] == '|') {
      const auto b = cur.find_first_not_of(' '), e = cur.find_last_not_of(' ');
      out.push_back(b == std::string::npos ? "" : cur.substr(b, e - b + 1));
      cur.clear();
    } else {
      cur += row[i];
    }
  }
  return out;
}

std::string unquote(const std::string& cell) {
  return cell.size() >= 2 && cell.front() == '`' && cell.back() == '`' ? cell.substr(1, cell.size() - 2)
                                                                       : cell;
}

std::vector<Row> catalogue() {
  std::ifstream in(std::string(DDISH_SOURCE_DIR) + "/docs/extreme-cases.md");
  std::string line;
  bool inside = false;
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    if (line.rfind("## ", 0) == 0) inside = line == "## Bad-input catalogue";
    if (!inside || line.rfind("| ", 0) != 0) continue;
    const std::vector<std::string> c = cells(line);
    if (c.size() != 4 || c[0].empty() || c[0].find_first_not_of("0123456789") != std::string::npos)
      continue;  // the header and the rule
    Row r;
    r.number = std::stoi(c[0]);
    const std::string command = unquote(c[1]);
    if (command.rfind("ddish ", 0) != 0) continue;  // GetsItsOneLine then misses the number
    r.args = command.substr(std::min<std::size_t>(6, command.size()));
    r.line = unquote(c[3]);
    rows.push_back(r);
  }
  return rows;
}

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (std::size_t at = 0; (at = s.find(from, at)) != std::string::npos; at += to.size())
    s.replace(at, from.size(), to);
  return s;
}

class BadInputCatalogue : public cli::TempDirTest, public ::testing::WithParamInterface<Row> {
 protected:
  BadInputCatalogue() : TempDirTest("ddish_catalogue_") {}

  std::string expand(const std::string& s) const {
    const std::string src = DDISH_SOURCE_DIR;
    std::string e = replace_all(s, "{scene}", src + "/scenes/cornell_box.gltf");
    e = replace_all(e, "{bad}", src + "/tests/app/bad_inputs");
    e = replace_all(e, "{tmp}", scratch_.string());
    return replace_all(e, "{src}", src);
  }
  fs::path scratch_;
};

TEST(BadInputCatalogueTable, HasAtLeastFortyRowsNumberedInOrder) {
  const std::vector<Row> rows = catalogue();
  ASSERT_GE(rows.size(), 40u) << "the catalogue lists at least 40 bad inputs";
  for (std::size_t i = 0; i < rows.size(); ++i) EXPECT_EQ(rows[i].number, int(i) + 1);
}

TEST_P(BadInputCatalogue, GetsItsOneLine) {
  const Row& row = GetParam();
  // A folder of its own: ddish's captured output lands in dir_, which some rows must not see.
  scratch_ = dir_ / "scratch";
  fs::create_directories(scratch_);
  std::ofstream(scratch_ / "a_file") << "x";
  SCOPED_TRACE("ddish " + row.args);
  const cli::Result r = run(expand(row.args));
  EXPECT_EQ(r.code, 2) << r.err;
  ASSERT_FALSE(r.err.empty());
  ASSERT_EQ(r.err.back(), '\n');
  const std::size_t start = r.err.rfind('\n', r.err.size() - 2) + 1;  // npos + 1 == 0
  const std::string last = r.err.substr(start, r.err.size() - 1 - start);
  EXPECT_EQ(r.err.find("ddish: error: "), start) << "not one error line, last: " << r.err;
  const std::string want = expand(row.line);
  const std::string ellipsis = "…";
  if (want.ends_with(ellipsis)) {
    const std::string prefix = want.substr(0, want.size() - ellipsis.size());
    EXPECT_EQ(last.substr(0, prefix.size()), prefix);
  } else {
    EXPECT_EQ(last, want);
  }
}

INSTANTIATE_TEST_SUITE_P(Rows, BadInputCatalogue, ::testing::ValuesIn(catalogue()),
                         [](const ::testing::TestParamInfo<Row>& row) {
                           return "row_" + std::to_string(row.param.number);
                         });

}  // namespace
