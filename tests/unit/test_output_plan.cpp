// The output plan: outputs distinct from inputs and from each other by the file they name (not
// the spelling), only regular files replaced, paths the filesystem can hold, directories this
// process can create files in; and the temporaries of killed runs removed, those of live ones
// kept.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <climits>
#include <filesystem>
#include <fstream>
#include <string>

#include "scatterlab/core/error.hpp"
#include "scatterlab/io/atomic_output.hpp"
#include "scatterlab/io/output_plan.hpp"

namespace scatterlab {
namespace {

namespace fs = std::filesystem;

class OutputPlanTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    directory_ = fs::temp_directory_path() /
                 ("scatterlab-output-plan-" + std::to_string(::getpid()) + "-" + info->name());
    fs::remove_all(directory_);
    fs::create_directories(directory_);
  }
  void TearDown() override { fs::remove_all(directory_); }

  fs::path file(const std::string& name, const std::string& text = "kept\n") const {
    const fs::path path = directory_ / name;
    std::ofstream(path) << text;
    return path;
  }

  fs::path directory_;
};

// The field of the InputError `plan.check()` throws, or "" when it passes.
std::string refused_field(const OutputPlan& plan) {
  try {
    plan.check();
  } catch (const InputError& error) {
    return error.field();
  }
  return "";
}

TEST_F(OutputPlanTest, DistinctPathsPass) {
  OutputPlan plan;
  plan.input("--scene", file("scene.toml"));
  plan.output_file("--out", directory_ / "run.h5");
  plan.output_file("--checkpoint", directory_ / "run.h5.checkpoint");
  EXPECT_EQ(refused_field(plan), "");
}

TEST_F(OutputPlanTest, OutputSpelledOtherwiseThanItsInputIsRefused) {
  const fs::path input = file("a.h5");
  OutputPlan plan;
  plan.input("FILES", input);
  plan.output_file("--out", directory_ / "sub" / ".." / "." / "a.h5");
  fs::create_directories(directory_ / "sub");
  EXPECT_EQ(refused_field(plan), "--out");
}

TEST_F(OutputPlanTest, HardLinkAndSymlinkToAnInputAreRefused) {
  const fs::path input = file("run.h5");
  fs::create_hard_link(input, directory_ / "hard.csv");
  fs::create_symlink(input, directory_ / "soft.csv");
  for (const char* name : {"hard.csv", "soft.csv"}) {
    OutputPlan plan;
    plan.rewritten_input("FILE", input);
    plan.output_file("--csv", directory_ / name);
    EXPECT_EQ(refused_field(plan), "--csv") << name;
  }
}

TEST_F(OutputPlanTest, TwoOutputsOnOneFileNameTheLater) {
  OutputPlan plan;
  plan.output_file("--out", directory_ / "o.h5");
  plan.output_file("--checkpoint", directory_ / "o.h5");
  EXPECT_EQ(refused_field(plan), "--checkpoint");
}

TEST_F(OutputPlanTest, OnlyRegularFilesAreReplaced) {
  ASSERT_EQ(::mkfifo((directory_ / "fifo").c_str(), 0600), 0);
  fs::create_directory(directory_ / "dir");
  // The device through a link, so that a wrong rename replaces the link, not /dev/null itself.
  fs::create_symlink("/dev/null", directory_ / "device");
  for (const fs::path& path : {directory_ / "fifo", directory_ / "dir", directory_ / "device"}) {
    OutputPlan plan;
    plan.output_file("--out", path);
    EXPECT_EQ(refused_field(plan), "--out") << path;
  }
}

TEST_F(OutputPlanTest, OutputDirectoryMustNotBeAFile) {
  OutputPlan plan;
  plan.output_directory("--out", file("notes.txt"));
  EXPECT_EQ(refused_field(plan), "--out");
  OutputPlan fresh;
  fresh.output_directory("--out-dir", directory_ / "new");
  fresh.output_file("--out-dir", directory_ / "new" / "albedo=0.5.h5");  // made by the command
  EXPECT_EQ(refused_field(fresh), "");
}

TEST_F(OutputPlanTest, MissingDirectoryIsRefused) {
  OutputPlan plan;
  plan.output_file("--checkpoint", directory_ / "missing" / "c.h5");
  EXPECT_EQ(refused_field(plan), "--checkpoint");
}

TEST_F(OutputPlanTest, ControlCharactersAndNulAreRefused) {
  for (const std::string& name : {std::string("a\nb.h5"), std::string("a\tb.h5"),
                                  std::string("a\x7f"), std::string("a\0b.h5", 6)}) {
    OutputPlan plan;
    plan.output_file("--out", directory_ / name);
    EXPECT_EQ(refused_field(plan), "--out") << name.size();
  }
  EXPECT_THROW(check_path_text("--out", ""), InputError);
}

TEST_F(OutputPlanTest, NamesAndPathsLongerThanTheFilesystemAllowsAreRefused) {
  const long name_max = ::pathconf(directory_.c_str(), _PC_NAME_MAX);
  ASSERT_GT(name_max, 0);
  const std::string longest(static_cast<std::size_t>(name_max), 'n');
  EXPECT_NO_THROW(check_path_text("--out", directory_ / longest));
  EXPECT_THROW(check_path_text("--out", directory_ / (longest + "n")), InputError);
  std::string deep;
  while (deep.size() < PATH_MAX) deep += "d/";
  EXPECT_THROW(check_path_text("--out", deep), InputError);
}

TEST_F(OutputPlanTest, SameFileComparesFilesNotSpellings) {
  const fs::path a = file("a.h5");
  EXPECT_TRUE(same_file(a, directory_ / "." / "a.h5"));
  EXPECT_FALSE(same_file(a, directory_ / "b.h5"));
  EXPECT_TRUE(same_file(directory_ / "x" / ".." / "new.h5", directory_ / "new.h5"));
}

// The InputError `plan.check()` throws, or "" when it passes.
std::string refusal(const OutputPlan& plan) {
  try {
    plan.check();
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

TEST_F(OutputPlanTest, DirectoryNoOneCanCreateFilesInIsRefusedForRootToo) {
  // /proc takes no new files, whatever the permissions and whoever asks.
  OutputPlan plan;
  plan.output_file("--out", "/proc/scatterlab-run.h5");
  const std::string message = refusal(plan);
  EXPECT_NE(message.find("--out"), std::string::npos) << message;
  EXPECT_NE(message.find("'/proc'"), std::string::npos) << message;
  OutputPlan directory;
  directory.output_directory("--out", "/proc/scatterlab-report");  // made under /proc
  EXPECT_EQ(refused_field(directory), "--out");
  EXPECT_FALSE(fs::exists("/proc/scatterlab-run.h5"));
}

TEST_F(OutputPlanTest, ReadOnlyDirectoryIsRefused) {
  if (::geteuid() == 0) GTEST_SKIP() << "root ignores permission bits";
  const fs::path locked = directory_ / "locked";
  fs::create_directory(locked);
  fs::permissions(locked, fs::perms::owner_read | fs::perms::owner_exec);
  OutputPlan plan;
  plan.output_file("--csv", locked / "table.csv");
  EXPECT_EQ(refused_field(plan), "--csv");
  fs::permissions(locked, fs::perms::owner_all);
}

TEST_F(OutputPlanTest, WritableDirectoriesPassAndKeepNoProbe) {
  OutputPlan plan;
  plan.output_file("--out", directory_ / "run.h5");
  plan.output_directory("--out-dir", directory_ / "sweep" / "deeper");  // made by the command
  EXPECT_EQ(refused_field(plan), "");
  EXPECT_TRUE(fs::is_empty(directory_));
}

TEST_F(OutputPlanTest, OutputDirectoriesAreMadeWithTheirParents) {
  OutputPlan plan;
  plan.output_directory("--out", directory_ / "a" / "b" / "c");
  plan.output_directory("--out", directory_ / "a");  // there by then: left as it is
  plan.check();
  plan.make_output_directories();
  EXPECT_TRUE(fs::is_directory(directory_ / "a" / "b" / "c"));
}

TEST_F(OutputPlanTest, ADirectoryOfOtherFilesIsRefusedAMarkedOrEmptyOneTaken) {
  fs::create_directories(directory_ / "empty");
  fs::create_directories(directory_ / "mine");
  std::ofstream(directory_ / "mine" / "report.md") << "my notes\n";
  OutputPlan into_empty, into_mine;
  into_empty.output_directory("--out", directory_ / "empty");
  into_mine.output_directory("--out", directory_ / "mine");
  EXPECT_EQ(refused_field(into_empty), "");
  EXPECT_EQ(refused_field(into_mine), "--out");
  // Once scatterlab has written there, a later run may write again (a re-run, a sweep resumed).
  into_empty.make_output_directories();
  EXPECT_TRUE(fs::is_regular_file(directory_ / "empty" / output_directory_marker));
  std::ofstream(directory_ / "empty" / "report.md") << "a report\n";
  EXPECT_EQ(refused_field(into_empty), "");
}

TEST_F(OutputPlanTest, ADirectoryThatCannotBeMadeNamesItsField) {
  OutputPlan plan;
  plan.output_directory("--out", file("notes.txt") / "sub");  // under a file: never, root or not
  try {
    plan.make_output_directories();
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "--out");
  }
  EXPECT_EQ(fs::file_size(directory_ / "notes.txt"), 5u);  // "kept\n", untouched
}

TEST_F(OutputPlanTest, StaleTemporariesOfDeadProcessesAreRemovedLiveOnesKept) {
  const fs::path out = directory_ / "o.h5";
  // A process id no process holds: beyond the largest the kernel gives out.
  const fs::path stale = file("o.h5.tmp-2147483646-0");
  const fs::path live = file("o.h5.tmp-" + std::to_string(::getpid()) + "-0");
  const fs::path unrelated = file("o.h5.tmp-notes");
  OutputPlan plan;
  plan.output_file("--out", out);
  const auto removed = plan.remove_stale_temporaries();
  ASSERT_EQ(removed.size(), 1u);
  EXPECT_EQ(removed.front(), stale);
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_TRUE(fs::exists(live));
  EXPECT_TRUE(fs::exists(unrelated));
}

}  // namespace
}  // namespace scatterlab
