// Writes that fail (a full disk, a quota, a file size limit): one error naming the output and the
// system's reason, the file that was there kept, no temporary left, and the process still able to
// end cleanly (a failed HDF5 flush used to leave a file that crashed HDF5's cleanup at exit). The
// failure is a file size limit with SIGXFSZ ignored, so that write() returns EFBIG.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <csignal>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "scatterlab/io/atomic_output.hpp"
#include "scatterlab/io/hdf5_file.hpp"
#include "scatterlab/render/image_file.hpp"

namespace scatterlab {
namespace {

namespace fs = std::filesystem;

constexpr rlim_t kLimitBytes = 8192;

class WriteFailureTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    directory_ = fs::temp_directory_path() /
                 ("scatterlab-write-failure-" + std::to_string(::getpid()) + "-" + info->name());
    fs::remove_all(directory_);
    fs::create_directories(directory_);
    old_ = directory_ / "kept.out";
    std::ofstream(old_) << "the previous result\n";
  }
  void TearDown() override {
    lift_limit();
    fs::remove_all(directory_);
  }

  void limit_file_size() {
    previous_handler_ = std::signal(SIGXFSZ, SIG_IGN);
    ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &previous_limit_), 0);
    rlimit limit = previous_limit_;
    limit.rlim_cur = kLimitBytes;
    ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &limit), 0);
    limited_ = true;
  }
  void lift_limit() {
    if (!limited_) return;
    ::setrlimit(RLIMIT_FSIZE, &previous_limit_);
    std::signal(SIGXFSZ, previous_handler_);
    limited_ = false;
  }

  std::string old_text() const {
    std::ifstream in(old_);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(directory_)) {
      names.push_back(entry.path().filename().string());
    }
    return names;
  }
  // The failure names the output (not its temporary) and the reason, and leaves things as they
  // were.
  void expect_clean_failure(const std::string& message) const {
    std::string quoted = "'";  // appended: GCC 12's -Wrestrict misfires on "'" + string
    quoted += old_.string();
    quoted += '\'';
    EXPECT_NE(message.find(quoted), std::string::npos) << message;
    EXPECT_NE(message.find(std::strerror(EFBIG)), std::string::npos) << message;
    EXPECT_EQ(message.find(".tmp-"), std::string::npos) << message;
    EXPECT_EQ(old_text(), "the previous result\n");
    EXPECT_EQ(entries(), std::vector<std::string>{"kept.out"});
  }

  fs::path directory_, old_;
  rlimit previous_limit_{};
  void (*previous_handler_)(int) = SIG_DFL;
  bool limited_ = false;
};

// What the command's error line would say, or "" when nothing failed.
template <typename Write>
std::string failure_of(Write write) {
  try {
    write();
  } catch (const std::runtime_error& error) {
    return error.what();
  }
  return "";
}

TEST_F(WriteFailureTest, Hdf5FileOverTheLimitFailsCleanly) {
  std::vector<double> values(20000);  // 160 kB of noise, which no filter compresses below the limit
  std::uint32_t state = 1;
  for (double& value : values) {
    state = state * 1664525u + 1013904223u;
    value = static_cast<double>(state) / 4294967296.0;
  }
  limit_file_size();
  const std::string message = failure_of([&] {
    AtomicOutput output(old_);
    hdf5::File file = hdf5::File::create(output.temporary_path());
    file.root().create_group("tallies").write_dataset("mean", values);
    file.close();
    output.commit();
  });
  lift_limit();
  expect_clean_failure(message);
  // HDF5 is left in order: another file can be written and read in this process.
  const fs::path next = directory_ / "next.h5";
  {
    hdf5::File file = hdf5::File::create(next);
    file.root().write_dataset("x", std::vector<double>{1.0, 2.0});
    file.close();
  }
  EXPECT_EQ(hdf5::File::open_read_only(next).root().read_dataset("x").values,
            (std::vector<double>{1.0, 2.0}));
}

TEST_F(WriteFailureTest, Hdf5FileAbandonedBeforeCloseWritesNothing) {
  {
    AtomicOutput output(old_);
    hdf5::File file = hdf5::File::create(output.temporary_path());
    file.root().create_group("tallies").write_dataset("mean", std::vector<double>(1000, 1.0));
  }  // an exception on the way: neither closed nor committed
  EXPECT_EQ(old_text(), "the previous result\n");
  EXPECT_EQ(entries(), std::vector<std::string>{"kept.out"});
}

TEST_F(WriteFailureTest, TextFileOverTheLimitFailsCleanly) {
  limit_file_size();
  const std::string message = failure_of([&] {
    write_text_file(old_, [](std::ostream& out) {
      for (int row = 0; row < 2000; ++row) out << row << ",0.125,0.25\n";
    });
  });
  lift_limit();
  expect_clean_failure(message);
}

TEST_F(WriteFailureTest, ImagesOverTheLimitFailCleanly) {
  Image image(128, 128);  // noise, which no encoder compresses below the limit
  std::uint32_t state = 1;
  for (double& value : image.values) {
    state = state * 1664525u + 1013904223u;
    value = static_cast<double>(state >> 8) / 16777216.0;
  }
  limit_file_size();
  const std::string exr = failure_of([&] { write_exr(image, old_); });
  lift_limit();
  expect_clean_failure(exr);
  limit_file_size();
  const std::string png = failure_of([&] { write_png(image, old_, 0.0, 2.2); });
  lift_limit();
  expect_clean_failure(png);
}

TEST(OutputName, NamesTheOutputOfThisProcesssTemporaries) {
  const std::string pid = std::to_string(::getpid());
  EXPECT_EQ(output_name("dir/run.h5.tmp-" + pid + "-3"), fs::path("dir/run.h5"));
  EXPECT_EQ(output_name("run.h5.tmp-" + pid + "-12"), fs::path("run.h5"));
  EXPECT_EQ(output_name("run.h5"), fs::path("run.h5"));
  EXPECT_EQ(output_name("run.h5.tmp-2147483646-3"), fs::path("run.h5.tmp-2147483646-3"));
  EXPECT_EQ(output_name("run.h5.tmp-" + pid + "-x"), fs::path("run.h5.tmp-" + pid + "-x"));
}

}  // namespace
}  // namespace scatterlab
