#pragma once
// Ranks as threads of one test process: the batch runner's multi-rank path (cell slices, the
// exchange of batch sums, gathering and dealing out state) tested without MPI, under the
// sanitizers too. Every collective posts its input on a shared board, waits for all ranks,
// reads what it needs and waits again before the board is reused.

#include <barrier>
#include <cstdint>
#include <functional>
#include <span>
#include <thread>
#include <vector>

#include "scatterlab/transport/communicator.hpp"

namespace scatterlab::testing {

class ThreadBoard {
 public:
  explicit ThreadBoard(int ranks)
      : ranks_(ranks), barrier_(ranks), arrays_(ranks), counts_(ranks), values_(ranks) {}

 private:
  friend class ThreadCommunicator;
  int ranks_;
  std::barrier<> barrier_;
  std::vector<std::span<const double>> arrays_;
  std::vector<std::vector<std::size_t>> counts_;
  std::vector<std::uint64_t> values_;
};

class ThreadCommunicator final : public Communicator {
 public:
  ThreadCommunicator(ThreadBoard& board, int rank) : board_(board), rank_(rank) {}
  int rank() const override { return rank_; }
  int size() const override { return board_.ranks_; }

  void all_to_all(std::span<const double> send, const std::vector<std::size_t>& send_counts,
                  std::span<double> receive, const std::vector<std::size_t>&) override {
    post(send, send_counts);
    std::size_t at = 0;
    for (std::size_t q = 0; q < board_.arrays_.size(); ++q) {
      std::size_t offset = 0;
      for (int p = 0; p < rank_; ++p) offset += board_.counts_[q][p];
      const std::size_t count = board_.counts_[q][rank_];
      std::copy_n(board_.arrays_[q].begin() + offset, count, receive.begin() + at);
      at += count;
    }
    board_.barrier_.arrive_and_wait();
  }

  std::vector<double> gather_to_root(std::span<const double> local,
                                     const std::vector<std::size_t>& counts) override {
    post(local, counts);
    std::vector<double> all;
    if (is_root()) {
      for (const auto& part : board_.arrays_) all.insert(all.end(), part.begin(), part.end());
    }
    board_.barrier_.arrive_and_wait();
    return all;
  }

  std::vector<double> scatter_from_root(std::span<const double> full,
                                        const std::vector<std::size_t>& counts) override {
    post(full, counts);
    std::size_t offset = 0;
    for (int p = 0; p < rank_; ++p) offset += counts[p];
    const std::span<const double> root = board_.arrays_[0];
    std::vector<double> part(root.begin() + offset, root.begin() + offset + counts[rank_]);
    board_.barrier_.arrive_and_wait();
    return part;
  }

  std::uint64_t sum(std::uint64_t value) override {
    return combine(value, [](std::uint64_t a, std::uint64_t b) { return a + b; });
  }
  std::uint64_t bitwise_or(std::uint64_t value) override {
    return combine(value, [](std::uint64_t a, std::uint64_t b) { return a | b; });
  }
  std::uint64_t broadcast_from_root(std::uint64_t value) override {
    board_.values_[rank_] = value;
    board_.barrier_.arrive_and_wait();
    const std::uint64_t result = board_.values_[0];
    board_.barrier_.arrive_and_wait();
    return result;
  }

 private:
  void post(std::span<const double> array, const std::vector<std::size_t>& counts) {
    board_.arrays_[rank_] = array;
    board_.counts_[rank_] = counts;
    board_.barrier_.arrive_and_wait();
  }

  std::uint64_t combine(std::uint64_t value,
                        const std::function<std::uint64_t(std::uint64_t, std::uint64_t)>& op) {
    board_.values_[rank_] = value;
    board_.barrier_.arrive_and_wait();
    std::uint64_t result = 0;
    for (const std::uint64_t v : board_.values_) result = op(result, v);
    board_.barrier_.arrive_and_wait();
    return result;
  }

  ThreadBoard& board_;
  int rank_;
};

// Runs body(communicator) on `ranks` threads, one per rank, and returns when all are done.
template <class Body>
void run_ranks(int ranks, Body body) {
  ThreadBoard board(ranks);
  std::vector<std::thread> threads;
  for (int rank = 0; rank < ranks; ++rank) {
    threads.emplace_back([&board, &body, rank] {
      ThreadCommunicator communicator(board, rank);
      body(communicator);
    });
  }
  for (std::thread& thread : threads) thread.join();
}

}  // namespace scatterlab::testing
