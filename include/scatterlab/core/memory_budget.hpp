#pragma once
// The memory a run may use, and the one check every command makes before it allocates: each
// command adds up what it will hold at its peak (a MemoryEstimate, filled from the same sizes
// that allocate: tally declarations, image sizes, dataset shapes) and check_memory refuses a run
// over the limit with one InputError naming the fields that drive the size and the figure.
//
// The limit is this machine's physical memory, or the cgroup's memory limit when that is lower
// (a container or a batch job), or the address space ulimit -v leaves when that is lower still,
// or what --memory-limit sets for the whole process.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace scatterlab {

// What a run will hold at its peak, part by part, in bytes. Sums saturate at 2^64 - 1 instead
// of wrapping, so that an absurd grid reads as absurd.
class MemoryEstimate {
 public:
  struct Part {
    std::string what;  // e.g. "4 arrays of 2.1e9 tally cells"
    std::uint64_t bytes;
  };

  void add(std::string what, std::uint64_t bytes);
  // `count` arrays of `values` doubles, described as "<count> x <what>".
  void add_doubles(const std::string& what, std::uint64_t values, std::uint64_t count = 1);

  std::uint64_t bytes() const { return total_; }
  const std::vector<Part>& parts() const { return parts_; }
  // "16.0 GiB for 4 arrays of ... + ...": the parts, largest first.
  std::string describe() const;

 private:
  std::vector<Part> parts_;
  std::uint64_t total_ = 0;
};

// a * b, or 2^64 - 1 when the product does not fit.
std::uint64_t saturating_product(std::uint64_t a, std::uint64_t b);

// The values in an array of this shape (1 for none), or 2^64 - 1 when they do not fit.
std::uint64_t value_count(std::span<const std::size_t> shape);

struct MemoryLimit {
  std::uint64_t bytes;
  std::string source;  // "the 23.4 GiB this machine has", "--memory-limit 512M", ...
};

// The machine's limit: physical memory, or the cgroup's (v2 memory.max, v1
// memory.limit_in_bytes) when lower, or what RLIMIT_AS (ulimit -v) leaves beyond the address
// space already mapped when lower still.
MemoryLimit machine_memory_limit();

// --memory-limit for this process; nullopt returns to the machine's limit.
void set_memory_limit(std::optional<std::uint64_t> bytes, const std::string& as_given = "");
// The limit in force: --memory-limit when given, else the machine's.
MemoryLimit memory_limit();

// "512M", "4G", "1.5GiB", "2T", "1000000" (bytes): K, M, G, T are powers of 1024. Throws
// InputError naming `field` for anything else, for 0 and for more than 2^63 bytes.
std::uint64_t parse_memory_size(const std::string& text, const std::string& field);

// "80.1 GiB", "512 MiB", "300 B".
std::string format_bytes(std::uint64_t bytes);

// Throws InputError(fields, "<describe()>, over <limit>", accepted) when `need` does not fit in
// memory_limit(). `fields` names what drives the size (e.g. "grid.r.bins x grid.z.bins"),
// `smaller` says how to ask for less (e.g. "fewer bins").
void check_memory(const MemoryEstimate& need, const std::string& fields,
                  const std::string& smaller);

}  // namespace scatterlab
