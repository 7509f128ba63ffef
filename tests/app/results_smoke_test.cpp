// The results report's reduced variant (`bash scripts/results.sh --quick`, tiny sizes, the
// Cornell box only) run end to end against this build: it must exit 0 and write RESULTS.md with
// every section and CSVs whose numbers are finite. No timing thresholds: only that the report and
// its figures exist.
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace {

namespace fs = std::filesystem;

std::string quote(const std::string& text) {
  std::string q;
  q += '\'';
  q += text;
  q += '\'';
  return q;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// One CSV line into fields; a field in double quotes may hold commas ("" is a quote).
std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        fields.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        fields.back() += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      fields.emplace_back();
    } else if (c != '\r') {
      fields.back() += c;
    }
  }
  return fields;
}

struct Table {
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;
};

Table read_csv(const fs::path& p) {
  Table t;
  std::ifstream in(p);
  std::string line;
  if (!std::getline(in, line)) return t;
  t.header = split_csv(line);
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const std::vector<std::string> f = split_csv(line);
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < t.header.size() && i < f.size(); ++i) row[t.header[i]] = f[i];
    t.rows.push_back(row);
  }
  return t;
}

// The number in `text`, or NaN when it is not a number (strtod must consume all of it).
double number(const std::string& text) {
  if (text.empty()) return std::nan("");
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  return (end && *end == '\0') ? v : std::nan("");
}

// Every listed column of every row holds a finite number.
void expect_finite(const Table& t, const std::vector<std::string>& columns, const std::string& what) {
  ASSERT_FALSE(t.rows.empty()) << what << " has no rows";
  for (const std::string& c : columns) {
    bool present = false;
    for (const std::string& h : t.header) present = present || h == c;
    ASSERT_TRUE(present) << what << " has no column " << c;
    for (std::size_t r = 0; r < t.rows.size(); ++r) {
      const std::string& v = t.rows[r].at(c);
      EXPECT_TRUE(std::isfinite(number(v))) << what << " row " << r << " column " << c << " = '" << v << "'";
    }
  }
}

TEST(ResultsSmoke, QuickReportHasEverySectionAndFiniteFigures) {
  const fs::path dir = fs::path(DDISH_BINARY_DIR) / ("results_smoke_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::string cmd = "DDISH_BUILD_DIR=";
  cmd += quote(DDISH_BINARY_DIR);
  cmd += " DDISH_RESULTS_CACHE=";
  cmd += quote((dir / "cache").string());
  cmd += " bash ";
  cmd += quote((fs::path(DDISH_SOURCE_DIR) / "scripts" / "results.sh").string());
  cmd += " --quick --out ";
  cmd += quote((dir / "report").string());
  cmd += " 2> ";
  cmd += quote((dir / "log.txt").string());
  const int status = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0)
      << "results.sh --quick failed:\n" << slurp(dir / "log.txt");

  const fs::path report = dir / "report" / "RESULTS.md";
  ASSERT_TRUE(fs::is_regular_file(report));
  const std::string md = slurp(report);
  for (const char* heading : {"## Machine", "## Headline figures", "## 1. Viewport scaling",
                              "## 2. Error against run time", "## 3. Dynamic light",
                              "## 4. Probe scheduling", "## 6. Soak"})
    EXPECT_NE(md.find(heading), std::string::npos) << "RESULTS.md lacks " << heading;
  EXPECT_EQ(md.find("failed"), std::string::npos) << "a step failed:\n" << md;
  EXPECT_NE(md.find("- Output: writing every frame"), std::string::npos)
      << "the headline lacks the output overhead:\n" << md;
  EXPECT_NE(md.find("- Memory: each view beyond a full batch adds"), std::string::npos)
      << "the headline lacks the memory figure:\n" << md;

  const fs::path results = dir / "report" / "results";
  expect_finite(read_csv(results / "scaling_cornell.csv"),
                {"views", "probe_update_ms", "upload_ms", "raster_ms", "frame_ms", "readback_ms",
                 "naive_ms", "speedup_vs_naive"},
                "scaling_cornell.csv");
  expect_finite(read_csv(results / "error_cornell.csv"), {"ms_per_frame", "psnr", "ssim", "rmse"},
                "error_cornell.csv");
  expect_finite(read_csv(results / "dynamic.csv"), {"frame", "rmse", "psnr", "ssim"}, "dynamic.csv");
  expect_finite(read_csv(results / "dynamic_summary.csv"), {"steady_rmse", "frame_ms"},
                "dynamic_summary.csv");
  expect_finite(read_csv(results / "soak.csv"), {"frame_ms", "rss_kb", "open_fds", "gpu_allocations"},
                "soak.csv");
  if (fs::is_regular_file(results / "trace_floor.csv"))
    expect_finite(read_csv(results / "trace_floor.csv"),
                  {"floor_rays", "floor_ms", "floor_mrays_s", "update_ms", "update_mrays_s"},
                  "trace_floor.csv");
  fs::remove_all(dir);
}

}  // namespace
