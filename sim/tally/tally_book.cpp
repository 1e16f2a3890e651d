#include "scatterlab/tally/tally_book.hpp"

#include <algorithm>
#include <span>
#include <stdexcept>
#include <string>

namespace scatterlab {
namespace {

std::size_t cells_of(const TallyDeclaration& d) {
  if (d.score == Score::exact) return 0;
  std::size_t cells = 1;
  for (const Filter& f : d.filters) cells *= f.bins();
  return cells;
}

// Whether `d` is scored by the fixed path of `score` along `coordinates`.
bool on_path(const TallyDeclaration& d, Score score, std::span<const Coordinate> coordinates) {
  return !d.chained && d.score == score && score != Score::exact &&
         std::equal(d.filters.begin(), d.filters.end(), coordinates.begin(), coordinates.end(),
                    [](const Filter& f, Coordinate c) { return f.coordinate() == c; });
}

// Names and descriptions of the per-order siblings, block by block.
constexpr const char* order_suffix[] = {"", "_unscattered", "_single", "_multiple"};
constexpr const char* order_scope[] = {"", " (unscattered light only)",
                                       " (light scattered exactly once)",
                                       " (light scattered twice or more)"};

// The declaration's dims, shape and measure of each cell (product of its filters' measures,
// left to right, from 1: 1 x m is m exactly).
TallyResult shaped(const TallyDeclaration& d, const std::string& name,
                   const std::string& description, const ReportedLength& length,
                   std::vector<double>& measure) {
  TallyResult t{name, {}, {}, d.units.text(length.unit), description, {}, {}, d.axes};
  measure.assign(1, 1.0);
  for (const Filter& f : d.filters) {
    t.dims.insert(t.dims.end(), f.dims.begin(), f.dims.end());
    t.shape.insert(t.shape.end(), f.shape.begin(), f.shape.end());
    std::vector<double> next;
    next.reserve(measure.size() * f.bins());
    for (const double m : measure) {
      for (const double b : f.measures) next.push_back(m * b);
    }
    measure = std::move(next);
  }
  return t;
}

}  // namespace

TallyBook::TallyBook(std::vector<TallyDeclaration> declarations, bool split_by_order)
    : declarations_(std::move(declarations)), split_by_order_(split_by_order) {
  declaration_offsets_.assign(declarations_.size(), absent);
  std::size_t next = 0;
  auto place = [&](bool by_order) {
    for (std::size_t i = 0; i < declarations_.size(); ++i) {
      const TallyDeclaration& d = declarations_[i];
      if (d.by_order != by_order || d.score == Score::exact) continue;
      if (d.chained && d.by_order)
        throw std::invalid_argument("TallyBook: a chained tally is not split by order: " + d.name);
      declaration_offsets_[i] = next;
      next += cells_of(d);
    }
  };
  // A fixed path scores one tally.
  for (std::size_t i = 0; i < declarations_.size(); ++i) {
    const TallyDeclaration& d = declarations_[i];
    std::vector<Coordinate> coordinates;
    for (const Filter& f : d.filters) coordinates.push_back(f.coordinate());
    for (std::size_t j = 0; j < i && !d.chained; ++j) {
      if (on_path(declarations_[j], d.score, coordinates)) {
        throw std::invalid_argument("TallyBook: two tallies of one fixed path: " +
                                    declarations_[j].name + " and " + d.name);
      }
    }
  }
  place(true);
  block_size_ = next;
  next = block_size_ * (split_by_order_ ? 4 : 1);
  place(false);
  size_ = next;
}

std::size_t TallyBook::offset(Score score, std::initializer_list<Coordinate> coordinates) const {
  for (std::size_t i = 0; i < declarations_.size(); ++i) {
    if (on_path(declarations_[i], score, {coordinates.begin(), coordinates.size()})) {
      return declaration_offsets_[i];
    }
  }
  return absent;
}

bool TallyBook::has_chain() const {
  for (const TallyDeclaration& d : declarations_) {
    if (d.chained) return true;
  }
  return false;
}

bool TallyBook::scores_volume() const {
  for (const TallyDeclaration& d : declarations_) {
    if (is_volume_score(d.score)) return true;
  }
  return false;
}

std::vector<TallyResult> TallyBook::finish(const std::vector<double>& raw_mean,
                                           const std::vector<double>& raw_stderr, double scale,
                                           const ReportedLength& length) const {
  std::vector<TallyResult> results;
  std::vector<double> measure;
  auto add = [&](std::size_t which, std::size_t block) {
    const TallyDeclaration& d = declarations_[which];
    TallyResult t = shaped(d, d.name + order_suffix[block], d.description + order_scope[block],
                           length, measure);
    if (d.score == Score::exact) {
      t.mean = {d.exact_value};
      t.stderr_of_mean = {0.0};
    } else {
      const std::size_t at = offset_of(which) + block * block_size_;
      t.mean.resize(measure.size());
      t.stderr_of_mean.resize(measure.size());
      for (std::size_t i = 0; i < measure.size(); ++i) {
        t.mean[i] = raw_mean[at + i] / measure[i] * scale;
        t.stderr_of_mean[i] = raw_stderr[at + i] / measure[i] * scale;
      }
    }
    // Into the reported length unit: after the scale, as its own product, so that a run in mfp,
    // and each tally with no length, keeps the bits it had.
    if (const double factor = length.factor(d.units); factor != 1.0) {
      for (double& value : t.mean) value *= factor;
      for (double& value : t.stderr_of_mean) value *= factor;
    }
    results.push_back(std::move(t));
  };
  const std::size_t blocks = split_by_order_ ? 4 : 1;
  for (std::size_t block = 0; block < blocks; ++block) {
    for (std::size_t i = 0; i < declarations_.size(); ++i) {
      if (declarations_[i].by_order) add(i, block);
    }
  }
  for (std::size_t i = 0; i < declarations_.size(); ++i) {
    if (!declarations_[i].by_order) add(i, 0);
  }
  return results;
}

}  // namespace scatterlab
