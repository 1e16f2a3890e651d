#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "scatterlab/core/error.hpp"
#include "scatterlab/report/report_writer.hpp"

namespace scatterlab::report {
namespace {

std::string read(const std::filesystem::path& path) {
  std::ifstream stream(path);
  std::stringstream text;
  text << stream.rdbuf();
  return text.str();
}

TEST(ReportWriter, CsvQuotesOnlyWhatNeedsIt) {
  const Table table{{"name", "value"}, {{"plain", "1.5"}, {"a, b", "say \"x\""}}};
  EXPECT_EQ(to_csv(table), "name,value\nplain,1.5\n\"a, b\",\"say \"\"x\"\"\"\n");
}

TEST(ReportWriter, MarkdownTableHasOneRuleRow) {
  const Table table{{"a", "b"}, {{"1", "2"}}};
  EXPECT_EQ(to_markdown(table), "| a | b |\n|---|---|\n| 1 | 2 |\n");
}

TEST(ReportWriter, SectionFailsOnAFailedCheckOrANan) {
  Section section;
  section.checks = {{"ok", true}};
  EXPECT_TRUE(section.passed());
  section.non_finite_values = 2;
  ASSERT_EQ(section.failures().size(), 1u);
  EXPECT_NE(section.failures()[0].find("2 NaN"), std::string::npos);
  section.non_finite_values = 0;
  section.checks.push_back({"slope -0.1 in [-0.7, -0.3]", false});
  EXPECT_EQ(section.failures(), std::vector<std::string>{"slope -0.1 in [-0.7, -0.3]"});
}

TEST(ReportWriter, WritesReportAndOneCsvPerSection) {
  const auto dir = std::filesystem::temp_directory_path() / "scatterlab-report-writer-test";
  std::filesystem::remove_all(dir);
  Section section;
  section.id = "demo";
  section.title = "Demo";
  section.table = {{"x"}, {{"1"}}};
  section.checks = {{"x is 1", false}};
  write_report(dir, "scatterlab report", {section});
  EXPECT_EQ(read(dir / "demo.csv"), "x\n1\n");
  const std::string markdown = read(dir / "report.md");
  EXPECT_NE(markdown.find("| [Demo](#demo) | FAIL |"), std::string::npos);
  EXPECT_NE(markdown.find("- x is 1"), std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST(ReportWriter, MakesMissingParentDirectories) {
  const auto dir = std::filesystem::temp_directory_path() / "scatterlab-report-writer-parents";
  std::filesystem::remove_all(dir);
  write_report(dir / "a" / "b", "", {});
  EXPECT_TRUE(std::filesystem::is_regular_file(dir / "a" / "b" / "report.md"));
  std::filesystem::remove_all(dir);
}

TEST(ReportWriter, DirectoryThatCannotBeMadeIsAnInputError) {
  // Under a regular file no directory can be made, whoever runs the test (root included).
  const auto file = std::filesystem::temp_directory_path() / "scatterlab-report-writer-file";
  std::ofstream(file) << "not a directory\n";
  EXPECT_THROW(write_report(file / "dir", "", {}), InputError);
  std::filesystem::remove(file);
}

}  // namespace
}  // namespace scatterlab::report
