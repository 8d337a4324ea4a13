// The processes of a run and the few collective operations surge needs. The only
// interface to MPI: built without SURGE_MPI it is one process and every call is trivial.
#pragma once
#include "surge/core/types.hpp"

#include <cstddef>
#include <vector>

namespace surge::domain {

namespace comm {
// MPI_Init / MPI_Finalize when built with MPI; nothing otherwise.
void init(int& argc, char**& argv);
void finalize();
[[nodiscard]] bool built_with_mpi();
[[nodiscard]] int rank();
[[nodiscard]] int size();
// Ends every process of the run at once (an error that not every process saw).
[[noreturn]] void abort(int code);

// Element-wise over processes, in place; every process gets the result.
void sum(double* x, std::size_t n);
void sum(Real* x, std::size_t n);
void min(double* x, std::size_t n);
// x[k] <- sum over processes of their x[k], added in rank order (the same bits everywhere).
void sum_in_rank_order(Real* x, std::size_t n);
void max(double* x, std::size_t n);
[[nodiscard]] double min(double x);
[[nodiscard]] double max(double x);
[[nodiscard]] double sum(double x);
// Seconds this process has spent inside collective calls (waiting for the others
// included): the load imbalance shows as the difference between processes.
[[nodiscard]] double collective_seconds();
// send[r]: bytes for process r; returns what each process sent this one, by sender.
[[nodiscard]] std::vector<std::vector<char>> all_to_all(const std::vector<std::vector<char>>& send);
// Every process's bytes, concatenated in rank order, on rank 0 (empty elsewhere).
[[nodiscard]] std::vector<char> gather(const std::vector<char>& mine);
} // namespace comm

} // namespace surge::domain
