// A half neighbour list with per-pair history (the DEM's, SPEC §3): each item lists its
// partners (at most Max) found by the grid within a cut, or kept beyond it by their
// history (a bond); each pair is numbered once, by its A item (the lower id), whose
// range [pair_begin, pair_begin + pair_count) holds the pairs' histories; `entry` maps
// each listed partner, on both sides, to the pair. A rebuild carries each pair's history
// over by partner id. Every walk over the list is here, in list order, so results do not
// depend on the thread count: each item writes only its own entries and its own pairs.
#pragma once
#include "surge/neighbour/uniform_grid.hpp"
#include "surge/par/parallel.hpp"

#include <cstdint>

namespace surge::neighbour {

inline constexpr std::uint32_t no_pair = 0xFFFFFFFFU;

struct PairListView {
  std::uint32_t* nbr;                     // Max per item: the listed partners' indices
  std::uint32_t* nnbr;                    // listed partners per item
  std::uint32_t* entry;                   // Max per item: the pair of each listed partner
  std::uint32_t *pair_begin, *pair_count; // the pairs an item is A of
  std::uint32_t* pair_b;                  // by pair: the B item's index (pair_partners)
};

// f(k, j, pair, i_is_a) for each listed partner j of item i, in list order (pair:
// no_pair where the partner's list was full and the pair was never numbered).
template <int Max, class F>
SURGE_HD inline void for_each_listed(const PairListView& l, const std::uint32_t* id, int i, F&& f) {
  const std::size_t base = static_cast<std::size_t>(i) * Max;
  const std::uint32_t idi = id[i];
  for (std::uint32_t k = 0; k < l.nnbr[i]; ++k) {
    const std::uint32_t j = l.nbr[base + k];
    f(k, static_cast<int>(j), l.entry[base + k], idi < id[j]);
  }
}

// f(k, j, pair) for each pair item i is A of (k: its rank among them), in list order:
// its range of pairs, numbered in list order, with their B items (pair_b; set by
// pair_partners after each rebuild), so no walk over the list and no test per entry.
template <class F>
SURGE_HD inline void for_each_own_pair(const PairListView& l, int i, F&& f) {
  const std::uint32_t p0 = l.pair_begin[i], count = l.pair_count[i];
  for (std::uint32_t k = 0; k < count; ++k) f(k, static_cast<int>(l.pair_b[p0 + k]), p0 + k);
}

// The old pair of item a (its A) with partner id b: searched among a's pairs of the last
// list, which stay where they were while the items are sorted (each item carries its
// range along).
template <class H>
SURGE_HD inline std::uint32_t find_pair(const PairListView& l, const H* old_hist, int a, std::uint32_t id_b) {
  const std::uint32_t p0 = l.pair_begin[a], p1 = p0 + l.pair_count[a];
  for (std::uint32_t p = p0; p < p1; ++p)
    if (old_hist[p].partner == id_b) return p;
  return no_pair;
}

// The points around which the grid is searched for the item at x (list_partners'
// `queries(x, query)` calls query(q) for each): x itself, by default; x and its periodic
// images for the DEM on periodic axes.
struct OneQuery {
  template <class Query>
  SURGE_HD void operator()(const Vec3& x, Query&& query) const {
    query(x);
  }
};

// Rebuild pass 1: each item's partners, the items j the grid finds within `search` of
// pos[i] (or of the queries' points) for which listed(i, j, r2, old) holds (old: the pair's history in the last
// list, or null), in the grid's order (queries, cells, then sorted index: the same on any
// thread count). Both items of a pair read the same old pair to decide, so they list each other
// or neither. entry[k] holds the old pair of an A-side entry (no_pair for a new pair);
// a_count[i] counts the A-side entries. Returns the most partners any item wanted (more
// than Max: some were left out).
template <int Max, class H, class Listed, class Queries = OneQuery>
int list_partners(const PairListView& l, const std::uint32_t* id, const Vec3* pos, int n, const GridView& g,
                  const H* old_hist, Real search, std::uint32_t* a_count, Listed listed, Queries queries = {}) {
  return par::parallel_reduce(
      n, 0,
      SURGE_LAMBDA(int i) {
        std::uint32_t* nb = l.nbr + static_cast<std::size_t>(i) * Max;
        std::uint32_t* entry = l.entry + static_cast<std::size_t>(i) * Max;
        const std::uint32_t idi = id[i];
        int cnt = 0, wanted = 0;
        std::uint32_t as_a = 0;
        const auto found = [&](int j, const Vec3&, Real r2) {
          if (j == i) return;
          const std::uint32_t idj = id[j];
          const bool i_is_a = idi < idj;
          const std::uint32_t old = i_is_a ? find_pair(l, old_hist, i, idj) : find_pair(l, old_hist, j, idi);
          if (!listed(i, j, r2, old == no_pair ? nullptr : &old_hist[old])) return;
          if (++wanted > Max) return;
          nb[cnt] = static_cast<std::uint32_t>(j);
          entry[cnt] = i_is_a ? old : no_pair;
          as_a += i_is_a ? 1U : 0U;
          ++cnt;
        };
        queries(pos[i], [&](const Vec3& q) { for_each_neighbour(g, q, search * search, found); });
        l.nnbr[i] = static_cast<std::uint32_t>(cnt);
        a_count[i] = as_a;
        return wanted;
      },
      par::Max{});
}

// Rebuild pass 2 (pair_begin now the exclusive scan of the A counts): each A-side entry
// gets the next pair of its item, with the old pair's history or a fresh one (H{}), its
// partner set to the B item's id.
template <int Max, class H>
void fill_pairs(const PairListView& l, const std::uint32_t* id, int n, const H* old_hist, H* hist) {
  par::parallel_for(
      n, SURGE_LAMBDA(int i) {
        const std::size_t base = static_cast<std::size_t>(i) * Max;
        std::uint32_t p = l.pair_begin[i];
        for (std::uint32_t k = 0; k < l.nnbr[i]; ++k) {
          const std::uint32_t j = l.nbr[base + k];
          if (id[i] > id[j]) continue;
          const std::uint32_t old = l.entry[base + k];
          H s = old != no_pair ? old_hist[old] : H{};
          s.partner = id[j];
          hist[p] = s;
          l.entry[base + k] = p++;
        }
      });
}

// Rebuild pass 3: each B-side entry takes the pair its partner's entry for it holds
// (no_pair when the partner's list was full).
template <int Max>
void link_pairs(const PairListView& l, const std::uint32_t* id, int n) {
  par::parallel_for(
      n, SURGE_LAMBDA(int i) {
        const std::size_t base = static_cast<std::size_t>(i) * Max;
        for (std::uint32_t k = 0; k < l.nnbr[i]; ++k) {
          const std::uint32_t j = l.nbr[base + k];
          if (id[i] < id[j]) continue;
          const std::size_t jb = static_cast<std::size_t>(j) * Max;
          std::uint32_t at = no_pair;
          for (std::uint32_t q = 0; q < l.nnbr[j]; ++q)
            if (l.nbr[jb + q] == static_cast<std::uint32_t>(i)) at = l.entry[jb + q];
          l.entry[base + k] = at;
        }
      });
}

// Each pair's B item (pair_b), from the A sides' entries: pairs walked without the list.
template <int Max>
void pair_partners(const PairListView& l, const std::uint32_t* id, int n) {
  par::parallel_for(
      n, SURGE_LAMBDA(int i) {
        for_each_listed<Max>(l, id, i, [&](std::uint32_t, int j, std::uint32_t p, bool i_is_a) {
          if (i_is_a) l.pair_b[p] = static_cast<std::uint32_t>(j);
        });
      });
}

} // namespace surge::neighbour
