#include "scatterlab/core/memory_budget.hpp"

#include <fmt/format.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <string_view>

#include "scatterlab/core/error.hpp"

namespace scatterlab {
namespace {

constexpr std::uint64_t saturated = std::numeric_limits<std::uint64_t>::max();

std::uint64_t saturating_sum(std::uint64_t a, std::uint64_t b) {
  return a > saturated - b ? saturated : a + b;
}

// The first line of a cgroup file as a byte count; nullopt for "max", a missing file or a
// v1 "unlimited" (a page-rounded 2^63 - 1).
std::optional<std::uint64_t> cgroup_value(const std::string& path) {
  std::ifstream file(path);
  std::string text;
  if (!(file >> text) || text.empty() || !std::isdigit(static_cast<unsigned char>(text[0]))) {
    return std::nullopt;
  }
  try {
    const std::uint64_t value = std::stoull(text);
    if (value >= (std::uint64_t{1} << 62)) return std::nullopt;
    return value;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

// The memory limits of this process's cgroups: from the lines of /proc/self/cgroup, v2's
// "0::/path" (memory.max) and v1's "N:memory:/path" (memory.limit_in_bytes), and those of the
// hierarchies' roots, which are the process's own inside a container.
std::optional<std::uint64_t> cgroup_limit() {
  std::optional<std::uint64_t> lowest;
  auto take = [&lowest](const std::string& path) {
    const std::optional<std::uint64_t> value = cgroup_value(path);
    if (value && (!lowest || *value < *lowest)) lowest = value;
  };
  std::ifstream file("/proc/self/cgroup");
  std::string line;
  while (std::getline(file, line)) {
    const std::size_t first = line.find(':'), second = line.find(':', first + 1);
    if (first == std::string::npos || second == std::string::npos) continue;
    const std::string controllers = line.substr(first + 1, second - first - 1);
    const std::string path = line.substr(second + 1);
    if (controllers.empty()) take("/sys/fs/cgroup" + path + "/memory.max");
    if (("," + controllers + ",").find(",memory,") != std::string::npos) {
      take("/sys/fs/cgroup/memory" + path + "/memory.limit_in_bytes");
    }
  }
  take("/sys/fs/cgroup/memory.max");
  take("/sys/fs/cgroup/memory/memory.limit_in_bytes");
  return lowest;
}

// RLIMIT_AS (ulimit -v) less the address space this process already maps (/proc/self/statm's
// first field, in pages): what a run may still allocate. nullopt without a limit.
struct AddressSpace {
  std::uint64_t limit;
  std::uint64_t left;
};
std::optional<AddressSpace> address_space_left() {
  rlimit address_space{};
  if (getrlimit(RLIMIT_AS, &address_space) != 0 || address_space.rlim_cur == RLIM_INFINITY) {
    return std::nullopt;
  }
  const auto limit = static_cast<std::uint64_t>(address_space.rlim_cur);
  std::uint64_t mapped_pages = 0;
  std::ifstream statm("/proc/self/statm");
  statm >> mapped_pages;
  const long page_size = sysconf(_SC_PAGESIZE);
  const std::uint64_t mapped =
      saturating_product(mapped_pages, page_size > 0 ? static_cast<std::uint64_t>(page_size) : 0);
  return AddressSpace{limit, mapped < limit ? limit - mapped : 0};
}

// The power of 1024 a size's unit stands for: none or B (bytes), or K, M, G, T alone or with
// B or iB after it ("4G", "4GB", "4GiB" are all 4 x 1024^3 bytes).
std::optional<int> unit_power(std::string_view unit) {
  if (unit.empty() || unit == "B") return 0;
  const std::size_t at = std::string_view("KMGT").find(
      static_cast<char>(std::toupper(static_cast<unsigned char>(unit[0]))));
  const std::string_view rest = unit.substr(1);
  if (at == std::string_view::npos || !(rest.empty() || rest == "B" || rest == "iB")) {
    return std::nullopt;
  }
  return static_cast<int>(at) + 1;
}

struct FlagLimit {
  std::uint64_t bytes;
  std::string as_given;
};
std::optional<FlagLimit> flag_limit;  // set once by the command line, before any work

}  // namespace

std::uint64_t saturating_product(std::uint64_t a, std::uint64_t b) {
  if (a == 0 || b == 0) return 0;
  return a > saturated / b ? saturated : a * b;
}

std::uint64_t value_count(std::span<const std::size_t> shape) {
  std::uint64_t values = 1;
  for (const std::size_t extent : shape) values = saturating_product(values, extent);
  return values;
}

void MemoryEstimate::add(std::string what, std::uint64_t bytes) {
  total_ = saturating_sum(total_, bytes);
  parts_.push_back({std::move(what), bytes});
}

void MemoryEstimate::add_doubles(const std::string& what, std::uint64_t values,
                                 std::uint64_t count) {
  const std::string text = count == 1 ? what : fmt::format("{} x {}", count, what);
  add(text, saturating_product(saturating_product(values, sizeof(double)), count));
}

std::string MemoryEstimate::describe() const {
  std::vector<const Part*> order;
  for (const Part& part : parts_) {
    if (part.bytes > 0) order.push_back(&part);
  }
  std::stable_sort(order.begin(), order.end(),
                   [](const Part* a, const Part* b) { return a->bytes > b->bytes; });
  std::string text;
  for (const Part* part : order) text += (text.empty() ? "" : " + ") + part->what;
  return fmt::format("{} for {}", format_bytes(total_), text.empty() ? "nothing" : text);
}

MemoryLimit machine_memory_limit() {
  const long pages = sysconf(_SC_PHYS_PAGES), page_size = sysconf(_SC_PAGESIZE);
  const std::uint64_t physical = pages > 0 && page_size > 0
                                     ? saturating_product(static_cast<std::uint64_t>(pages),
                                                          static_cast<std::uint64_t>(page_size))
                                     : saturated;
  MemoryLimit limit{physical, fmt::format("the {} this machine has", format_bytes(physical))};
  const std::optional<std::uint64_t> cgroup = cgroup_limit();
  if (cgroup && *cgroup < limit.bytes) {
    limit = {*cgroup, fmt::format("the {} this process's cgroup allows", format_bytes(*cgroup))};
  }
  const std::optional<AddressSpace> space = address_space_left();
  if (space && space->left < limit.bytes) {
    limit = {space->left, fmt::format("the {} of address space that ulimit -v ({}) leaves",
                                      format_bytes(space->left), format_bytes(space->limit))};
  }
  return limit;
}

void set_memory_limit(std::optional<std::uint64_t> bytes, const std::string& as_given) {
  if (bytes) {
    flag_limit = FlagLimit{*bytes, as_given};
  } else {
    flag_limit.reset();
  }
}

MemoryLimit memory_limit() {
  if (flag_limit) {
    return {flag_limit->bytes, fmt::format("--memory-limit {} ({})", flag_limit->as_given,
                                           format_bytes(flag_limit->bytes))};
  }
  return machine_memory_limit();
}

std::uint64_t parse_memory_size(const std::string& text, const std::string& field) {
  const std::string accepted =
      "a size such as 512M, 4G or 1.5GiB (K, M, G, T: powers of 1024; a plain number is "
      "bytes), above 0 and at most 2^63 bytes";
  const std::size_t digits = text.find_first_not_of("0123456789.");
  const std::string number = text.substr(0, digits);
  const std::optional<int> power = unit_power(
      digits == std::string::npos ? std::string_view() : std::string_view(text).substr(digits));
  double bytes = std::numeric_limits<double>::quiet_NaN();
  if (!number.empty() && power && std::count(number.begin(), number.end(), '.') <= 1 &&
      number != ".") {
    bytes = std::floor(std::ldexp(std::strtod(number.c_str(), nullptr), 10 * *power));
  }
  if (!(bytes >= 1.0 && bytes <= 0x1p63)) {
    throw InputError(field, fmt::format("got \"{}\"", text), accepted);
  }
  return static_cast<std::uint64_t>(bytes);
}

std::string format_bytes(std::uint64_t bytes) {
  if (bytes == saturated) return "more than 16 EiB";
  constexpr const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  double value = static_cast<double>(bytes);
  std::size_t unit = 0;
  while (value >= 1024.0 && unit + 1 < std::size(units)) {
    value /= 1024.0;
    ++unit;
  }
  if (unit == 0) return fmt::format("{} B", bytes);
  return fmt::format("{:.1f} {}", value, units[unit]);
}

void check_memory(const MemoryEstimate& need, const std::string& fields,
                  const std::string& smaller) {
  const MemoryLimit limit = memory_limit();
  if (need.bytes() <= limit.bytes) return;
  throw InputError(fields, fmt::format("{}, over {}", need.describe(), limit.source),
                   fmt::format("{} to fit in {}; or --memory-limit SIZE of at least {} where "
                               "that memory is there",
                               smaller, format_bytes(limit.bytes), format_bytes(need.bytes())));
}

}  // namespace scatterlab
