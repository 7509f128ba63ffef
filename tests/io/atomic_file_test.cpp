// io/atomic_file.h: a file appears whole or not at all, a failed write leaves the old file and
// no temporary, a file size limit is reported with the system's reason, folder checks fail
// early with one line, and remove_partial_files removes the temporaries of writes in progress.
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "io/atomic_file.h"

namespace {

namespace fs = std::filesystem;
using namespace ddish;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<std::string> names_in(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

class AtomicFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("ddish_atomic_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) +
            "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(AtomicFile, WritesTheWholeFileAndNothingElse) {
  const std::string bytes(100000, 'a');
  io::write_file_atomically(dir_ / "f.bin", bytes);
  EXPECT_EQ(slurp(dir_ / "f.bin"), bytes);
  EXPECT_EQ(names_in(dir_), std::vector<std::string>{"f.bin"});
  io::write_file_atomically(dir_ / "f.bin", "new");  // replaces
  EXPECT_EQ(slurp(dir_ / "f.bin"), "new");
  EXPECT_EQ(names_in(dir_), std::vector<std::string>{"f.bin"});
}

TEST_F(AtomicFile, TheTemporaryIsHiddenBesideTheTarget) {
  fs::path seen;
  io::write_atomically(dir_ / "img.png", [&](const fs::path& t) {
    seen = t;
    std::ofstream(t) << "x";
    EXPECT_FALSE(fs::exists(dir_ / "img.png"));  // not visible before it is complete
  });
  EXPECT_EQ(seen.parent_path(), dir_);
  EXPECT_EQ(seen.filename().string().rfind(".img.png.ddish-", 0), 0u) << seen;
  EXPECT_TRUE(seen.string().ends_with(".part")) << seen;
  EXPECT_FALSE(fs::exists(seen));
  EXPECT_EQ(slurp(dir_ / "img.png"), "x");
}

TEST_F(AtomicFile, AFailedWriteKeepsTheOldFileAndRemovesTheTemporary) {
  io::write_file_atomically(dir_ / "f.json", "old");
  try {
    io::write_atomically(dir_ / "f.json", [](const fs::path& t) {
      std::ofstream(t) << "half";
      throw std::runtime_error("the encoder gave up");
    });
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "cannot write " + (dir_ / "f.json").string() + ": the encoder gave up");
  }
  EXPECT_EQ(slurp(dir_ / "f.json"), "old");
  EXPECT_EQ(names_in(dir_), std::vector<std::string>{"f.json"});
}

TEST_F(AtomicFile, AWriterThatCreatesNothingIsAnError) {
  EXPECT_THROW(io::write_atomically(dir_ / "f", [](const fs::path&) {}), std::runtime_error);
  EXPECT_TRUE(names_in(dir_).empty());
}

TEST_F(AtomicFile, FileSizeLimitGivesTheSystemsReason) {
  // In a child: the limit and the ignored SIGXFSZ must not outlive the test.
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::signal(SIGXFSZ, SIG_IGN);
    rlimit lim{4096, 4096};
    setrlimit(RLIMIT_FSIZE, &lim);
    int code = 1;
    try {
      io::write_file_atomically(dir_ / "big", std::string(10000, 'b'));
    } catch (const std::runtime_error& e) {
      const std::string m = e.what();
      code = m == "cannot write " + (dir_ / "big").string() + ": File too large" ? 0 : 3;
    }
    _exit(code);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << "1: no exception, 3: another message";
  EXPECT_TRUE(names_in(dir_).empty());  // the temporary went with the failure
}

TEST_F(AtomicFile, FolderChecksFailEarlyWithTheReason) {
  io::check_writable_folder(dir_ / "new" / "deeper");  // created
  EXPECT_TRUE(fs::is_directory(dir_ / "new" / "deeper"));
  EXPECT_TRUE(names_in(dir_ / "new" / "deeper").empty());  // the check file is gone
  std::ofstream(dir_ / "file") << "x";
  try {
    io::check_writable_folder(dir_ / "file" / "sub");
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "cannot write to output folder " +
                                         (dir_ / "file" / "sub").string() + ": Not a directory");
  }
  EXPECT_THROW(io::check_writable_file(dir_ / "file" / "t.json"), std::runtime_error);
  EXPECT_THROW(io::check_writable_file(dir_), std::runtime_error);  // a folder, not a file
  io::check_writable_file(dir_ / "t.json");
  EXPECT_FALSE(fs::exists(dir_ / "t.json"));
}

TEST_F(AtomicFile, RemovePartialFilesRemovesTheTemporariesInProgress) {
  fs::path seen;
  EXPECT_THROW(io::write_atomically(dir_ / "f",
                                    [&](const fs::path& t) {
                                      seen = t;
                                      std::ofstream(t) << "half";
                                      io::remove_partial_files();  // as a signal handler would
                                      EXPECT_FALSE(fs::exists(t));
                                    }),
               std::runtime_error);
  EXPECT_TRUE(names_in(dir_).empty());
  // Finished writes are no longer registered: their files stay.
  io::write_file_atomically(dir_ / "g", "whole");
  io::remove_partial_files();
  EXPECT_EQ(slurp(dir_ / "g"), "whole");
}

}  // namespace

namespace {

TEST_F(AtomicFile, AWriterInPiecesAppearsOnlyOnCommit) {
  io::write_file_atomically(dir_ / "t.json", "old");
  {
    io::AtomicFileWriter w(dir_ / "t.json");
    w.write("{\"frames\": [");
    for (int k = 0; k < 1000; ++k) {
      if (k > 0) w.write(",");
      w.write(std::to_string(k));
    }
    // In progress: the real name still holds the old file, and one hidden temporary sits beside it.
    EXPECT_EQ(slurp(dir_ / "t.json"), "old");
    EXPECT_EQ(names_in(dir_).size(), 2u);
    w.write("]}");
    w.commit();
    EXPECT_THROW(w.write("late"), std::runtime_error);
  }
  const std::string text = slurp(dir_ / "t.json");
  EXPECT_EQ(text.substr(0, 15), "{\"frames\": [0,1");
  EXPECT_EQ(text.substr(text.size() - 6), ",999]}");
  EXPECT_EQ(names_in(dir_), std::vector<std::string>{"t.json"});
}

TEST_F(AtomicFile, AWriterDestroyedWithoutCommitLeavesTheOldFileAlone) {
  io::write_file_atomically(dir_ / "t.json", "old");
  {
    io::AtomicFileWriter w(dir_ / "t.json");
    w.write("half a docu");
  }
  EXPECT_EQ(slurp(dir_ / "t.json"), "old");
  EXPECT_EQ(names_in(dir_), std::vector<std::string>{"t.json"});
  try {
    io::AtomicFileWriter w(dir_ / "missing" / "t.json");
    FAIL() << "a writer into a missing folder was made";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot write"), std::string::npos) << e.what();
  }
}

}  // namespace
