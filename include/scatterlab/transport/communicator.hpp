#pragma once
// The few collective operations the batch runner needs between processes (ranks). A run on one
// process uses SerialCommunicator; `mpirun` runs get an MPI implementation from
// scatterlab/parallel/world.hpp. Collectives are called by every rank, in the same order, by one
// thread of a rank at a time (not always the same one).

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace scatterlab {

class Communicator {
 public:
  virtual ~Communicator() = default;

  virtual int rank() const = 0;
  virtual int size() const = 0;
  bool is_root() const { return rank() == 0; }

  // Rank q sends send[displacement_q(p), + counts(q, p)) to every rank p and receives from
  // every rank q, in rank order, into `receive`: send_counts[p] values go to rank p,
  // receive_counts[q] values come from rank q.
  virtual void all_to_all(std::span<const double> send, const std::vector<std::size_t>& send_counts,
                          std::span<double> receive,
                          const std::vector<std::size_t>& receive_counts) = 0;
  // The root gets the ranks' `local` arrays concatenated in rank order (counts[q] from rank q);
  // other ranks get an empty vector.
  virtual std::vector<double> gather_to_root(std::span<const double> local,
                                             const std::vector<std::size_t>& counts) = 0;
  // Rank q gets full[offset_q, offset_q + counts[q]) of the root's `full`.
  virtual std::vector<double> scatter_from_root(std::span<const double> full,
                                                const std::vector<std::size_t>& counts) = 0;
  virtual std::uint64_t sum(std::uint64_t value) = 0;
  virtual std::uint64_t bitwise_or(std::uint64_t value) = 0;
  virtual std::uint64_t broadcast_from_root(std::uint64_t value) = 0;
};

// One process: every collective is the identity.
class SerialCommunicator final : public Communicator {
 public:
  int rank() const override { return 0; }
  int size() const override { return 1; }
  void all_to_all(std::span<const double> send, const std::vector<std::size_t>&,
                  std::span<double> receive, const std::vector<std::size_t>&) override {
    std::copy(send.begin(), send.end(), receive.begin());
  }
  std::vector<double> gather_to_root(std::span<const double> local,
                                     const std::vector<std::size_t>&) override {
    return {local.begin(), local.end()};
  }
  std::vector<double> scatter_from_root(std::span<const double> full,
                                        const std::vector<std::size_t>&) override {
    return {full.begin(), full.end()};
  }
  std::uint64_t sum(std::uint64_t value) override { return value; }
  std::uint64_t bitwise_or(std::uint64_t value) override { return value; }
  std::uint64_t broadcast_from_root(std::uint64_t value) override { return value; }
};

}  // namespace scatterlab
