#include "scatterlab/io/mcml_input.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <string_view>
#include <system_error>
#include <unordered_map>
#include <utility>

#include "scatterlab/core/error.hpp"
#include "scatterlab/io/text_file.hpp"
#include "scatterlab/transport/grid_checks.hpp"

// The format and its limits follow MCML 1.2.2's reader (mcmlio.c: FindDataLine, ReadNumRuns,
// ReadParm, CheckParm) and section 9.1 of the MCML manual (Wang & Jacques 1992), "File of input
// data": the version is always 1.0, the format always A, integers must be written as integers.
// Where MCML reads a line with sscanf and quietly ignores what does not fit, this reader refuses
// it, because each such case runs something other than what the file seems to say: "1e6" photons
// reads as 1 photon (the manual warns of it), a layer line with four numbers leaves d unset, a
// sixth number on a layer line means the columns are shifted.

namespace scatterlab {
namespace {

namespace fs = std::filesystem;

// One line of the file that holds data: its number (from 1) and its words before any '#'.
struct DataLine {
  int number = 0;
  std::vector<std::string_view> words;
};

// A value the file must hold, as MCML names it, and what is accepted for it.
struct Field {
  std::string name;
  std::string accepted;
};

const std::string kWholeFromOne = "a whole number >= 1, in digits";
const std::string kPositive = "a finite number > 0";
const std::string kNonNegative = "a finite number >= 0 (1/cm)";
const std::string kLength = "a finite number > 0 (cm)";
const std::string kAnisotropy =
    "a finite number with |g| < 1 (the Henyey-Greenstein phase function exists only there)";
const std::string kBins = fmt::format("a whole number from 1 to {}, in digits", max_axis_bins);

// '#' starts a comment anywhere on a line; what is left is split at spaces and tabs (a '\r' of a
// Windows line end counts as a space). MCML skips a line whose first non-blank character is '#'
// or which is blank; the words MCML reads on a data line are the first ones, so the comment after
// them is never read either.
std::vector<DataLine> data_lines(std::string_view text, int& line_count) {
  std::vector<DataLine> lines;
  constexpr std::string_view blanks = " \t\r\f\v";
  int number = 0;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    ++number;
    std::string_view content = text.substr(start, end - start);
    content = content.substr(0, content.find('#'));
    DataLine line{number, {}};
    std::size_t at = content.find_first_not_of(blanks);
    while (at != std::string_view::npos) {
      const std::size_t word_end = std::min(content.find_first_of(blanks, at), content.size());
      line.words.push_back(content.substr(at, word_end - at));
      at = content.find_first_not_of(blanks, word_end);
    }
    if (!line.words.empty()) lines.push_back(std::move(line));
    start = end + 1;
  }
  line_count = number;
  return lines;
}

// A word as a message shows it: bytes that are not printable ASCII as \xNN.
std::string shown(std::string_view word) {
  std::string text = "'";
  for (const char c : word) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte >= 0x20 && byte < 0x7f) {
      text += c;
    } else {
      text += fmt::format("\\x{:02X}", byte);
    }
  }
  return text + "'";
}

// A decimal number as C's strtod reads it (an optional sign, digits, point, exponent), the whole
// word and nothing else; hexadecimal is not MCML's and is refused. nullopt for anything else.
std::optional<double> read_real(std::string_view word) {
  if (word.size() > 1 && word.front() == '+' && word[1] != '-') word.remove_prefix(1);
  double value = 0;
  const auto [end, error] =
      std::from_chars(word.data(), word.data() + word.size(), value, std::chars_format::general);
  if (error != std::errc{} || end != word.data() + word.size()) return std::nullopt;
  return value;
}

// A whole number in decimal digits with an optional sign, nullopt for anything else (a point,
// an exponent, or more than a 64-bit integer holds).
std::optional<long long> read_whole(std::string_view word) {
  if (word.size() > 1 && word.front() == '+' && word[1] != '-') word.remove_prefix(1);
  long long value = 0;
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
  if (error != std::errc{} || end != word.data() + word.size()) return std::nullopt;
  return value;
}

class McmlReader {
 public:
  McmlReader(std::string origin, std::string_view text)
      : origin_(std::move(origin)), lines_(data_lines(text, line_count_)) {}

  std::vector<McmlRun> read_all() {
    // MCML skips the version line unread; checking it here refuses an MCML 2.0 file, whose
    // layout differs from the first line on.
    const Field version_field{"file version",
                              "1.0 (the MCML 1.x input file; MCML 2.0 files, which start "
                              "\"mcmli2.0\", are not read)"};
    const DataLine version = take({version_field});
    const std::optional<double> number = read_real(version.words[0]);
    if (!number || *number != 1.0) {
      fail(version.number, version_field.name, "got " + shown(version.words[0]),
           version_field.accepted);
    }
    const Field runs_field{"number of runs", kWholeFromOne};
    const DataLine runs_line = take({runs_field});
    const long long run_count = whole(runs_line, 0, runs_field, 1);

    std::vector<McmlRun> runs;
    std::unordered_map<std::string, std::size_t> run_of_output;
    for (long long i = 0; i < run_count; ++i) {
      runs.push_back(read_run());
      // As MCML's CheckParm: two runs writing one file would lose the first run's results.
      const auto [earlier, is_new] = run_of_output.emplace(runs.back().output_file, runs.size());
      if (!is_new) {
        fail(
            runs.back().line, "output file",
            fmt::format("{} is also the output of run {} (line {})", shown(runs.back().output_file),
                        earlier->second, runs[earlier->second - 1].line),
            "a different output file for each run");
      }
    }
    // MCML stops reading after the last declared run; data after it is most likely a run the
    // count left out, and is refused rather than dropped.
    if (next_ < lines_.size()) {
      fail(lines_[next_].number, "number of runs",
           fmt::format("line {} declares {} run{}, but more data follows the last one",
                       runs_line.number, run_count, run_count == 1 ? "" : "s"),
           "as many runs as the number of runs declares, then only comments or blank lines");
    }
    return runs;
  }

 private:
  [[noreturn]] void fail(int line, const std::string& field, const std::string& problem,
                         const std::string& accepted) const {
    throw InputError(fmt::format("{}:{} {}", origin_, line, field), problem, accepted);
  }

  // The next data line, holding exactly one word per field.
  DataLine take(const std::vector<Field>& fields) {
    if (next_ >= lines_.size()) {
      fail(line_count_ + 1, fields.front().name, "missing: the file ends before it",
           fields.front().accepted);
    }
    DataLine line = lines_[next_++];
    if (line.words.size() < fields.size()) {
      const Field& missing = fields[line.words.size()];
      fail(line.number, missing.name,
           fmt::format("missing: the line holds {} of its {} values", line.words.size(),
                       fields.size()),
           missing.accepted);
    }
    if (line.words.size() > fields.size()) {
      fail(line.number, fields.back().name,
           fmt::format("is followed by {} on the same line", shown(line.words[fields.size()])),
           fmt::format("{} value{} on this line, then an optional # comment", fields.size(),
                       fields.size() == 1 ? "" : "s"));
    }
    return line;
  }

  long long whole(const DataLine& line, std::size_t index, const Field& field, long long least,
                  long long most = std::numeric_limits<long long>::max()) const {
    const std::optional<long long> value = read_whole(line.words[index]);
    if (!value || *value < least || *value > most) {
      fail(line.number, field.name, "got " + shown(line.words[index]), field.accepted);
    }
    return *value;
  }

  // A finite number within the bounds: > low (or >= low when low_included), and < high.
  double real(const DataLine& line, std::size_t index, const Field& field, double low,
              bool low_included, double high = std::numeric_limits<double>::infinity()) const {
    const std::optional<double> value = read_real(line.words[index]);
    const bool in_range = value && std::isfinite(*value) &&
                          (low_included ? *value >= low : *value > low) && *value < high;
    if (!in_range) fail(line.number, field.name, "got " + shown(line.words[index]), field.accepted);
    return *value + 0.0;  // "-0" is 0, and echoes as "0" in the .mco
  }

  McmlRun read_run() {
    McmlRun run;
    const Field name{"output file", "a file name without spaces, then the format A"};
    const Field format{"format", "A (ASCII, the one format MCML's output readers take)"};
    const DataLine name_line = take({name, format});
    run.line = name_line.number;
    for (const char c : name_line.words[0]) {
      const auto byte = static_cast<unsigned char>(c);
      if (byte < 0x21 || byte > 0x7e) {
        fail(name_line.number, name.name, "got " + shown(name_line.words[0]),
             "a file name of printable ASCII characters");
      }
    }
    run.output_file = std::string(name_line.words[0]);
    // MCML reads the format letter with toupper(): 'a' is ASCII as well.
    const std::string_view letter = name_line.words[1];
    if (letter != "A" && letter != "a") {
      fail(name_line.number, format.name, "got " + shown(letter), format.accepted);
    }
    run.file_format = 'A';

    // MCML holds the count in a C long; a larger one could not be echoed into the .mco and read
    // back by MCML's CONV.
    const Field photons{"photons",
                        "a whole number from 1 to 9223372036854775807, in digits (MCML reads "
                        "\"1e6\" as 1 photon)"};
    const DataLine photons_line = take({photons});
    run.photons = static_cast<std::uint64_t>(whole(photons_line, 0, photons, 1));

    const Field dz{"dz", kLength}, dr{"dr", kLength};
    const DataLine grid_steps = take({dz, dr});
    run.dz = real(grid_steps, 0, dz, 0.0, false);
    run.dr = real(grid_steps, 1, dr, 0.0, false);

    // MCML itself keeps Nz, Nr, Na in a C short (at most 32767); the larger grids scatterlab
    // runs are written faithfully, but MCML's own programs cannot read them back.
    const Field nz{"Nz", kBins}, nr{"Nr", kBins}, na{"Na", kBins};
    const DataLine bins = take({nz, nr, na});
    run.nz = static_cast<int>(whole(bins, 0, nz, 1, max_axis_bins));
    run.nr = static_cast<int>(whole(bins, 1, nr, 1, max_axis_bins));
    run.na = static_cast<int>(whole(bins, 2, na, 1, max_axis_bins));

    const Field layer_count{"number of layers", kWholeFromOne};
    const DataLine layers_line = take({layer_count});
    const long long layers = whole(layers_line, 0, layer_count, 1);

    const Field above{"n above", kPositive};
    run.n_above = real(take({above}), 0, above, 0.0, false);
    for (long long i = 1; i <= layers; ++i) {
      const std::string prefix = fmt::format("layer {} ", i);
      const Field n{prefix + "n", kPositive}, mua{prefix + "mua", kNonNegative},
          mus{prefix + "mus", kNonNegative}, g{prefix + "g", kAnisotropy}, d{prefix + "d", kLength};
      const DataLine line = take({n, mua, mus, g, d});
      McmlLayer layer{};
      layer.n = real(line, 0, n, 0.0, false);
      layer.mu_a = real(line, 1, mua, 0.0, true);
      layer.mu_s = real(line, 2, mus, 0.0, true);
      layer.g = real(line, 3, g, -1.0, false, 1.0);
      layer.thickness = real(line, 4, d, 0.0, false);
      run.layers.push_back(layer);
    }
    const Field below{"n below", kPositive};
    run.n_below = real(take({below}), 0, below, 0.0, false);
    return run;
  }

  std::string origin_;
  int line_count_ = 0;
  std::vector<DataLine> lines_;
  std::size_t next_ = 0;
};

}  // namespace

std::vector<McmlRun> read_mcml_input(const fs::path& path) {
  const std::string field = "mcml input";
  std::string text;
  try {
    text = read_scene_file(path, field);
  } catch (const InputError& error) {
    // The shared check speaks of scene (TOML) files; the problem it found stands, the accepted
    // text is this file's. what() is "<field>: <problem>; accepted: <accepted>" (core/error.hpp).
    const std::string_view what = error.what();
    const std::size_t accepted = what.rfind("; accepted: ");
    const std::size_t begin = error.field().size() + 2;
    const std::string problem(accepted != std::string_view::npos && accepted > begin
                                  ? what.substr(begin, accepted - begin)
                                  : what);
    throw InputError(field, problem, "a regular MCML input file (.mci) of at most 1 MiB");
  }
  return parse_mcml_input(text, path.string());
}

std::vector<McmlRun> parse_mcml_input(std::string_view text, const std::string& origin) {
  return McmlReader(origin, text).read_all();
}

LayeredSlabSpec layered_slab_spec(const McmlRun& run) {
  LayeredSlabSpec spec;
  spec.length_unit = "cm";
  spec.layers.clear();
  for (const McmlLayer& l : run.layers) {
    spec.layers.push_back({l.mu_a, l.mu_s, l.g, l.n, l.thickness, std::nullopt});
  }
  spec.n_above = run.n_above;
  spec.n_below = run.n_below;
  spec.r = UniformAxis{0.0, run.dr * run.nr, run.nr};
  spec.z = UniformAxis{0.0, run.dz * run.nz, run.nz};
  spec.theta_o = UniformAxis{0.0, std::numbers::pi / 2.0, run.na};
  spec.run.photons = run.photons;
  return spec;
}

}  // namespace scatterlab
