#include "scatterlab/io/merge.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>
#include <string_view>
#include <utility>

#include "dimension_scales.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/core/memory_budget.hpp"
#include "scatterlab/io/atomic_output.hpp"
#include "scatterlab/io/hdf5_file.hpp"
#include "scatterlab/io/simulation_file.hpp"
#include "scatterlab/tally/pooled_statistics.hpp"
#include "scatterlab/transport/run_settings.hpp"

namespace scatterlab {
namespace {

namespace fs = std::filesystem;

constexpr const char* kAccepted =
    "runs of the same scene that differ only in seed, photons, batches and threads";

// Parameters that may differ between the runs being merged.
const std::set<std::string> kPerRun = {"photons", "batches", "seed", "seeds", "threads"};

void copy_attribute(const hdf5::Object& from, hdf5::Object& to, const std::string& name) {
  switch (from.attribute_type(name)) {
    case hdf5::AttributeType::string:
      return to.write_string_attribute(name, from.read_string_attribute(name));
    case hdf5::AttributeType::floating:
      return to.write_double_attribute(name, from.read_double_attribute(name));
    case hdf5::AttributeType::signed_integer:
      return to.write_int64_attribute(name, from.read_int64_attribute(name));
    case hdf5::AttributeType::unsigned_integer:
      return to.write_uint64_attribute(name, from.read_uint64_attribute(name));
    case hdf5::AttributeType::other:
      break;
  }
  throw std::runtime_error(from.location() + ": attribute '" + name + "' has an unknown type");
}

// Every attribute but those of dimension scales, which write_dimension_scales makes anew.
void copy_attributes(const hdf5::Object& from, hdf5::Object& to) {
  for (const std::string& name : from.attribute_names()) {
    if (!is_dimension_scale_attribute(name)) copy_attribute(from, to, name);
  }
}

[[noreturn]] void mismatch(const std::string& field, const fs::path& a, const std::string& in_a,
                           const fs::path& b, const std::string& in_b) {
  throw InputError(
      field, fmt::format("{} has {} but {} has {}", b.string(), in_b, a.string(), in_a), kAccepted);
}

// Parameter name -> value as `scatterlab info` shows it, less those that may differ.
std::map<std::string, std::string> shared_parameters(const FileSummary& summary) {
  std::map<std::string, std::string> values;
  for (const auto& [name, value] : summary.parameters) {
    if (!kPerRun.count(name)) values[name] = value;
  }
  return values;
}

void check_parameters(const FileSummary& first, const FileSummary& other) {
  const auto a = shared_parameters(first), b = shared_parameters(other);
  for (const auto& [name, value] : a) {
    const auto it = b.find(name);
    const std::string field = fmt::format("parameters.{}", name);
    if (it == b.end()) mismatch(field, first.path, value, other.path, "none");
    if (it->second != value) mismatch(field, first.path, value, other.path, it->second);
  }
  for (const auto& [name, value] : b) {
    if (!a.count(name)) {
      mismatch(fmt::format("parameters.{}", name), first.path, "none", other.path, value);
    }
  }
}

// The seeds a file ran: /parameters seed, or a merged file's list "seeds". Each is a seed a run
// can have, [0, 2^63 - 1]: anything else (a negative number, a word) was not written by a run.
std::vector<std::uint64_t> seeds_of(const fs::path& path, const hdf5::Group& parameters) {
  std::vector<std::string> texts;
  if (parameters.has_attribute("seed")) {
    // Read as what it is stored as: HDF5 would clip a negative integer read as unsigned to 0.
    switch (parameters.attribute_type("seed")) {
      case hdf5::AttributeType::unsigned_integer:
        texts.push_back(std::to_string(parameters.read_uint64_attribute("seed")));
        break;
      case hdf5::AttributeType::signed_integer:
        texts.push_back(std::to_string(parameters.read_int64_attribute("seed")));
        break;
      case hdf5::AttributeType::string:
        texts.push_back(parameters.read_string_attribute("seed"));
        break;
      default:
        texts.push_back("of another type");
    }
  } else {
    const std::string list =
        parameters.has_attribute("seeds") ? parameters.read_string_attribute("seeds") : "";
    for (std::size_t at = 0; at < list.size();) {
      std::size_t next = list.find(',', at);
      if (next == std::string::npos) next = list.size();
      texts.push_back(list.substr(at, next - at));
      at = next + 1;
    }
  }
  std::vector<std::uint64_t> seeds;
  for (const std::string& text : texts) {
    std::uint64_t seed = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), seed);
    if (error != std::errc{} || end != text.data() + text.size() || seed > max_seed) {
      throw InputError("FILES", fmt::format("{} has seed {}", path.string(), text),
                       fmt::format("runs whose seeds are each {}", seed_accepted));
    }
    seeds.push_back(seed);
  }
  return seeds;
}

struct Input {
  fs::path path;
  FileSummary summary;
  hdf5::File file;
  double batches;
  std::uint64_t photons;
};

std::uint64_t count(const hdf5::Group& group, const char* name) {
  return static_cast<std::uint64_t>(group.read_int64_attribute(name));
}

// The batches a file's tallies are the mean of: all of them unless it is partial.
double batches_of(const hdf5::File& file) {
  const hdf5::Group& root = file.root();
  if (root.has_attribute("batches_done")) return static_cast<double>(count(root, "batches_done"));
  return static_cast<double>(count(root.open_group("parameters"), "batches"));
}

const char* const input_accepted =
    "complete runs written by scatterlab simulate or searchlight (format_version 1), with finite "
    "tallies";

// A file merge can pool: complete, of the format this build reads, with counts that agree with
// each other, and finite tallies. Merged files are inputs too: their totals obey the same rules.
void check_input(const fs::path& path, const hdf5::File& file, const FileSummary& summary) {
  const auto refuse = [&path](const std::string& problem) {
    throw InputError("FILES", fmt::format("{} {}", path.string(), problem), input_accepted);
  };
  const hdf5::Group& root = file.root();
  const hdf5::Group parameters = root.open_group("parameters");
  const std::int64_t batches = parameters.read_int64_attribute("batches");
  const std::int64_t photons = parameters.read_int64_attribute("photons");
  const std::int64_t done =
      root.has_attribute("batches_done") ? root.read_int64_attribute("batches_done") : batches;
  if (summary.partial) {
    refuse(
        fmt::format("is partial ({} of {} batches, from a run that was stopped): finish it "
                    "with --resume, then merge",
                    done, batches));
  }
  if (batches < 1 || done != batches) {
    refuse(
        fmt::format("is inconsistent: batches_done {} but parameters.batches {}", done, batches));
  }
  if (summary.photons_run != photons || photons < batches) {
    refuse(fmt::format("is inconsistent: photons_run {} but parameters.photons {} in {} batches",
                       summary.photons_run, photons, batches));
  }
  if (summary.scattering_events < 0) {
    refuse(fmt::format("is inconsistent: scattering_events {}", summary.scattering_events));
  }
}

// The tallies whose mean may be negative: the vector irradiance's components and the first
// moment of the absorption depth. Every other tally counts power, fluence or radiance.
bool is_signed_tally(const std::string& name) {
  return name == "flux" || name == "absorbed_mean_depth";
}

// An input's tally as it is pooled: finite means, non-negative unless the tally is signed, and
// finite, non-negative standard errors.
void check_input_tally(const fs::path& path, const std::string& name, const hdf5::Array& mean,
                       const hdf5::Array& stderr_of_mean) {
  for (const auto& [values, dataset] :
       {std::pair{&mean.values, "mean"}, std::pair{&stderr_of_mean.values, "stderr"}}) {
    const bool non_negative = std::string_view(dataset) == "stderr" || !is_signed_tally(name);
    const auto bad = std::find_if(values->begin(), values->end(), [&](double v) {
      return !std::isfinite(v) || (non_negative && v < 0.0);
    });
    if (bad != values->end()) {
      throw InputError("FILES",
                       fmt::format("{} has {} in tallies/{}/{}[{}]", path.string(), *bad, name,
                                   dataset, bad - values->begin()),
                       input_accepted);
    }
  }
}

// A dataset copied whole into `to` under its own name: values, shape and attributes.
void copy_dataset(const hdf5::Dataset& from, hdf5::Group& to, const std::string& name) {
  const hdf5::Array array = from.read();
  hdf5::Dataset copy = to.write_dataset(name, array.values, array.shape);
  copy_attributes(from, copy);
}

// An attribute as text, to compare two files' models.
std::string attribute_text(const hdf5::Object& object, const std::string& name) {
  if (object.attribute_type(name) == hdf5::AttributeType::string) {
    return object.read_string_attribute(name);
  }
  return fmt::format("{}", object.read_double_attribute(name));
}

// Each model under /models as text (its attributes, and every curve's shape, attributes and
// values, exactly): two files' models agree when these are equal.
std::map<std::string, std::string> model_texts(const hdf5::File& file) {
  std::map<std::string, std::string> texts;
  if (!file.root().has_member("models")) return texts;
  const hdf5::Group models = file.root().open_group("models");
  for (const std::string& model : models.member_names()) {
    const hdf5::Group group = models.open_group(model);
    std::string text;
    for (const std::string& name : group.attribute_names()) {
      text += fmt::format("@{}={}\n", name, attribute_text(group, name));
    }
    for (const std::string& curve : curve_names(group)) {
      const hdf5::Dataset dataset = group.open_dataset(curve);
      const hdf5::Array array = dataset.read();
      text += fmt::format("{} [{}] {}\n", curve, fmt::join(array.shape, ","),
                          fmt::join(array.values, ","));
      for (const std::string& name : dataset.attribute_names()) {
        if (is_dimension_scale_attribute(name)) continue;
        text += fmt::format("{}@{}={}\n", curve, name, attribute_text(dataset, name));
      }
    }
    texts[model] = std::move(text);
  }
  return texts;
}

// Why the inputs' /models cannot be kept (the first model in which two inputs differ), or empty
// when they all hold the same models.
std::string models_disagreement(const std::vector<Input>& inputs) {
  const std::map<std::string, std::string> first = model_texts(inputs.front().file);
  for (std::size_t i = 1; i < inputs.size(); ++i) {
    const std::map<std::string, std::string> other = model_texts(inputs[i].file);
    if (other == first) continue;
    std::string model;
    for (const auto& [name, text] : first) {
      const auto it = other.find(name);
      if (it == other.end() || it->second != text) {
        model = name;
        break;
      }
    }
    if (model.empty()) {
      for (const auto& [name, text] : other) {
        if (!first.count(name)) {
          model = name;
          break;
        }
      }
    }
    return fmt::format("{} and {} differ in /models/{}", inputs.front().path.string(),
                       inputs[i].path.string(), model);
  }
  return {};
}

void copy_models(const hdf5::File& from, hdf5::Group& root) {
  const hdf5::Group models = from.root().open_group("models");
  hdf5::Group target = root.create_group("models");
  for (const std::string& model : models.member_names()) {
    const hdf5::Group group = models.open_group(model);
    hdf5::Group node = target.create_group(model);
    for (const std::string& name : group.attribute_names()) copy_attribute(group, node, name);
    for (const std::string& curve : curve_names(group)) {
      copy_dataset(group.open_dataset(curve), node, curve);
    }
  }
}

void check_grid(const Input& first, const Input& other) {
  const hdf5::Group a = first.file.root().open_group("grid");
  const hdf5::Group b = other.file.root().open_group("grid");
  if (first.summary.phi_folded != other.summary.phi_folded) {
    mismatch("grid.fold_phi", first.path, fmt::format("{}", first.summary.phi_folded), other.path,
             fmt::format("{}", other.summary.phi_folded));
  }
  if (a.member_names() != b.member_names()) {
    mismatch("grid", first.path, fmt::format("axes {}", fmt::join(a.member_names(), ",")),
             other.path, fmt::format("axes {}", fmt::join(b.member_names(), ",")));
  }
  for (const std::string& axis : a.member_names()) {
    const hdf5::Array x = a.read_dataset(axis), y = b.read_dataset(axis);
    if (x.values != y.values) {
      mismatch(fmt::format("grid.{}", axis), first.path,
               fmt::format("{} bins", x.values.size() - 1), other.path,
               fmt::format("{} bins{}", y.values.size() - 1,
                           x.values.size() == y.values.size() ? " with other edges" : ""));
    }
  }
}

// The groups inside /parameters (a slab's layers: one dataset per property) hold physics the
// runs must share, value for value.
void check_parameter_groups(const Input& first, const Input& other) {
  const hdf5::Group a = first.file.root().open_group("parameters");
  const hdf5::Group b = other.file.root().open_group("parameters");
  if (a.member_names() != b.member_names()) {
    mismatch("parameters", first.path, fmt::format("groups {}", fmt::join(a.member_names(), ",")),
             other.path, fmt::format("groups {}", fmt::join(b.member_names(), ",")));
  }
  for (const std::string& group : a.member_names()) {
    const hdf5::Group ga = a.open_group(group), gb = b.open_group(group);
    if (ga.member_names() != gb.member_names()) {
      mismatch(fmt::format("parameters.{}", group), first.path,
               fmt::format("{}", fmt::join(ga.member_names(), ",")), other.path,
               fmt::format("{}", fmt::join(gb.member_names(), ",")));
    }
    for (const std::string& name : ga.member_names()) {
      const hdf5::Array x = ga.read_dataset(name), y = gb.read_dataset(name);
      if (x.values != y.values) {
        // A mesh's vertices are thousands of values: name the first that differs.
        const auto say = [&x, &y](const std::vector<double>& v) {
          if (x.values.size() <= 8 || x.values.size() != y.values.size()) {
            return fmt::format("{}", fmt::join(v, ", "));
          }
          const auto at = static_cast<std::size_t>(
              std::mismatch(x.values.begin(), x.values.end(), y.values.begin()).first -
              x.values.begin());
          return fmt::format("{} values, value {} being {}", v.size(), at, v[at]);
        };
        mismatch(fmt::format("parameters.{}.{}", group, name), first.path, say(x.values),
                 other.path, say(y.values));
      }
    }
  }
}

// Before the merged file is begun: the largest tally is held at once as the first input's mean,
// one input's mean and stderr, the pooled batch sets and the pooled error (below).
void check_merge_memory(const hdf5::Group& tallies) {
  std::uint64_t largest = 0;
  for (const std::string& name : tallies.member_names()) {
    largest = std::max(largest, value_count(tallies.open_group(name).open_dataset("mean").shape()));
  }
  MemoryEstimate need;
  need.add_doubles(fmt::format("arrays of the largest tally ({} values)", largest), largest,
                   4 + sizeof(BatchSet) / sizeof(double));
  check_memory(need, "FILES", "smaller tallies");
}

}  // namespace

MergeSummary merge_simulation_files(const std::vector<fs::path>& paths, const fs::path& output,
                                    const std::string& command) {
  if (paths.size() < 2) {
    throw InputError("FILES", fmt::format("got {} file(s)", paths.size()),
                     "two or more files written by scatterlab simulate");
  }
  AtomicOutput out(output);  // a bad output path fails before anything is read
  std::vector<Input> inputs;
  std::map<std::uint64_t, fs::path> seeds;
  MergeSummary summary;
  for (const fs::path& path : paths) {
    FileSummary summary_of_input = read_file_summary(path, "FILES");  // InputError unless sound
    hdf5::File file = hdf5::File::open_read_only(path);
    check_input(path, file, summary_of_input);
    const double batches = batches_of(file);
    if (batches < 2) {
      throw InputError("FILES", fmt::format("{} holds {} batch(es)", path.string(), batches),
                       "files of at least 2 batches (a standard error needs two)");
    }
    const std::uint64_t photons = count(file.root(), "photons_run");
    for (const std::uint64_t seed : seeds_of(path, file.root().open_group("parameters"))) {
      const auto [it, fresh] = seeds.emplace(seed, path);
      if (!fresh) {
        throw InputError("parameters.seed",
                         fmt::format("{} and {} both ran seed {}: their photons are the same, "
                                     "not independent",
                                     it->second.string(), path.string(), seed),
                         "runs with different seeds");
      }
    }
    inputs.push_back({path, std::move(summary_of_input), std::move(file), batches, photons});
  }

  const Input& first = inputs.front();
  const hdf5::Group first_tallies = first.file.root().open_group("tallies");
  const double per_batch = static_cast<double>(first.photons) / first.batches;
  for (const Input& other : inputs) {
    summary.photons += other.photons;
    summary.batches += static_cast<std::uint64_t>(other.batches);
    const double ratio = static_cast<double>(other.photons) / other.batches / per_batch;
    summary.unequal_batches = summary.unequal_batches || std::abs(ratio - 1.0) > 0.01;
    if (&other == &first) continue;
    check_parameters(first.summary, other.summary);
    check_parameter_groups(first, other);
    check_grid(first, other);
    const hdf5::Group tallies = other.file.root().open_group("tallies");
    if (tallies.member_names() != first_tallies.member_names()) {
      mismatch("tallies", first.path,
               fmt::format("{}", fmt::join(first_tallies.member_names(), ",")), other.path,
               fmt::format("{}", fmt::join(tallies.member_names(), ",")));
    }
  }

  check_merge_memory(first_tallies);
  // Models depend on the parameters and grid alone, which agree by now; files written by other
  // versions of scatterlab may still hold other curves, and then none is kept.
  summary.models_dropped = models_disagreement(inputs);
  const bool keep_models = summary.models_dropped.empty() && first.file.root().has_member("models");

  hdf5::File file = hdf5::File::create(out.temporary_path());
  hdf5::Group& root = file.root();
  const hdf5::Group& first_root = first.file.root();
  double wall_seconds = 0.0;
  std::uint64_t scattering_events = 0;
  std::string merged_from;
  for (const Input& input : inputs) {
    wall_seconds += input.file.root().read_double_attribute("wall_seconds");
    scattering_events += count(input.file.root(), "scattering_events");
    if (!merged_from.empty()) merged_from += '\n';
    merged_from += input.path.string();
  }
  root.write_string_attribute("format", "scatterlab");
  root.write_int64_attribute("format_version", kSimulationFormatVersion);
  root.write_string_attribute("scatterlab_version", SCATTERLAB_VERSION);
  root.write_string_attribute("command", command);
  root.write_string_attribute("created", iso8601_now());
  root.write_double_attribute("wall_seconds", wall_seconds);
  root.write_int64_attribute("photons_run", static_cast<std::int64_t>(summary.photons));
  root.write_int64_attribute("scattering_events", static_cast<std::int64_t>(scattering_events));
  root.write_int64_attribute("batches_done", static_cast<std::int64_t>(summary.batches));
  root.write_bool_attribute("partial", false);
  root.write_string_attribute("merged_from", merged_from);

  {  // groups close before the file does
    // Parameters: the first input's, with the totals and every seed.
    hdf5::Group parameters = root.create_group("parameters");
    const hdf5::Group first_parameters = first_root.open_group("parameters");
    std::string seed_list;
    for (const auto& entry : seeds) {
      if (!seed_list.empty()) seed_list += ',';
      seed_list += std::to_string(entry.first);
    }
    for (const std::string& name : first_parameters.attribute_names()) {
      if (name == "photons") {
        parameters.write_int64_attribute(name, static_cast<std::int64_t>(summary.photons));
      } else if (name == "batches") {
        parameters.write_int64_attribute(name, static_cast<std::int64_t>(summary.batches));
      } else if (name == "seed" || name == "seeds") {
        parameters.write_string_attribute("seeds", seed_list);
      } else if (name != "threads") {
        copy_attribute(first_parameters, parameters, name);
      }
    }
    for (const std::string& name : first_parameters.member_names()) {
      const hdf5::Group from = first_parameters.open_group(name);
      hdf5::Group to = parameters.create_group(name);
      for (const std::string& dataset : from.member_names()) {
        copy_dataset(from.open_dataset(dataset), to, dataset);
      }
    }

    hdf5::Group grid = root.create_group("grid");
    const hdf5::Group first_grid = first_root.open_group("grid");
    for (const std::string& name : first_grid.attribute_names())
      copy_attribute(first_grid, grid, name);
    for (const std::string& axis : first_grid.member_names()) {
      copy_dataset(first_grid.open_dataset(axis), grid, axis);
    }

    hdf5::Group tallies = root.create_group("tallies");
    for (const std::string& name : first_tallies.member_names()) {
      const hdf5::Group from = first_tallies.open_group(name);
      hdf5::Group node = tallies.create_group(name);
      for (const std::string& attribute : from.attribute_names())
        copy_attribute(from, node, attribute);
      hdf5::Array mean = from.read_dataset("mean");
      std::vector<BatchSet> pooled(mean.values.size());
      for (const Input& input : inputs) {
        const hdf5::Group tally = input.file.root().open_group("tallies").open_group(name);
        const hdf5::Array m = tally.read_dataset("mean"), e = tally.read_dataset("stderr");
        if (m.shape != mean.shape || e.shape != mean.shape) {
          mismatch(fmt::format("tallies.{}", name), first.path, "another shape", input.path,
                   "this shape");
        }
        check_input_tally(input.path, name, m, e);
        for (std::size_t i = 0; i < pooled.size(); ++i) {
          const BatchSet run =
              BatchSet::from_standard_error(m.values[i], e.values[i], input.batches);
          pooled[i] = &input == &first ? run : pool(pooled[i], run);
        }
      }
      std::vector<double> error(pooled.size());
      for (std::size_t i = 0; i < pooled.size(); ++i) {
        mean.values[i] = pooled[i].mean;
        error[i] = pooled[i].standard_error();
      }
      check_finite_tally(name, mean.values, error);
      for (const char* dataset : {"mean", "stderr"}) {
        const hdf5::Dataset source = from.open_dataset(dataset);
        hdf5::Dataset target = node.write_dataset(
            dataset, std::string(dataset) == "mean" ? mean.values : error, mean.shape);
        copy_attributes(source, target);
      }
      if (from.has_member("axes")) {  // a declared tally's own axes (tally_result.hpp)
        const hdf5::Group axes = from.open_group("axes");
        hdf5::Group copy = node.create_group("axes");
        for (const std::string& axis : axes.member_names()) {
          copy_dataset(axes.open_dataset(axis), copy, axis);
        }
      }
    }
  }
  if (keep_models) copy_models(first.file, root);
  write_dimension_scales(root);
  file.close();
  out.commit();
  return summary;
}

}  // namespace scatterlab
