#include "scatterlab/report/report_writer.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "scatterlab/core/error.hpp"
#include "scatterlab/io/atomic_output.hpp"
#include "scatterlab/io/simulation_file.hpp"

namespace scatterlab::report {
namespace {

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string joined(const std::vector<std::string>& cells, const std::string& separator,
                   std::string (*format)(const std::string&)) {
  std::string line;
  for (std::size_t i = 0; i < cells.size(); ++i) line += (i ? separator : "") + format(cells[i]);
  return line;
}

std::string as_is(const std::string& text) {
  return text;
}

void write_text(const std::filesystem::path& path, const std::string& text) {
  write_text_file(path, [&text](std::ostream& stream) { stream << text; });
}

}  // namespace

std::string to_csv(const Table& table) {
  std::string text = joined(table.columns, ",", csv_field) + "\n";
  for (const auto& row : table.rows) text += joined(row, ",", csv_field) + "\n";
  return text;
}

std::string to_markdown(const Table& table) {
  std::string text = "| " + joined(table.columns, " | ", as_is) + " |\n|";
  for (std::size_t i = 0; i < table.columns.size(); ++i) text += "---|";
  text += "\n";
  for (const auto& row : table.rows) text += "| " + joined(row, " | ", as_is) + " |\n";
  return text;
}

std::vector<std::filesystem::path> write_report(const std::filesystem::path& directory,
                                                const std::string& command_line,
                                                const std::vector<Section>& sections) {
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error || !std::filesystem::is_directory(directory)) {
    throw InputError("out", fmt::format("cannot create directory {}", directory.string()),
                     "a directory, or a path where one can be made");
  }

  std::vector<std::filesystem::path> written;
  std::string markdown = fmt::format(
      "# scatterlab accuracy report\n\nscatterlab {}, {}\n\n`{}`\n\n| section | result |\n"
      "|---|---|\n",
      SCATTERLAB_VERSION, iso8601_now(), command_line);
  for (const Section& section : sections) {
    markdown += fmt::format("| [{}](#{}) | {} |\n", section.title, section.id,
                            section.passed() ? "pass" : "FAIL");
  }
  for (const Section& section : sections) {
    markdown += fmt::format(
        "\n<a id=\"{}\"></a>\n## {}\n\n**Reference.** {}\n\n**Tolerance.** {}\n\n{}\n{}\n"
        "Data: [`{}.csv`]({}.csv)\n",
        section.id, section.title, section.reference, section.tolerance, section.findings,
        to_markdown(section.table), section.id, section.id);
    for (const Figure& figure : section.figures) {
      written.push_back(directory / (figure.id + ".png"));
      write_png(figure.plot, written.back());
      // The title's line break (io/plot.hpp) is a space in the image's text.
      std::string alt = figure.plot.title;
      std::replace(alt.begin(), alt.end(), '\n', ' ');
      markdown += fmt::format("\n![{}]({}.png)\n", alt, figure.id);
    }
    const auto failures = section.failures();
    if (!failures.empty()) {
      markdown += "\n**Failed:**\n\n";
      for (const std::string& failure : failures) markdown += "- " + failure + "\n";
    }
    written.push_back(directory / (section.id + ".csv"));
    write_text(written.back(), to_csv(section.table));
  }
  written.push_back(directory / "report.md");
  write_text(written.back(), markdown);
  return written;
}

}  // namespace scatterlab::report
