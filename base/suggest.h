#pragma once
// "did you mean ...?" for every place that looks a name up (techniques,
// parameters, scenes, choices, subcommands, options): the candidate closest
// to a mistyped word, when it is close enough to be a typo of it.
#include <algorithm>
#include <string>
#include <vector>

namespace oit {

// Edits (insert, delete, substitute, swap two neighbours) between a and b:
// the optimal string alignment distance, so "lsit" is one edit from "list".
inline size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
  for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t substitute = d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, substitute});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  }
  return d[a.size()][b.size()];
}

// The candidate closest to `word`, or "" when none is a likely typo of it:
// at most a third of the word's letters (at least one) edited, or one of
// the two a prefix of the other ("benchmark" -> "bench", "--frame" ->
// "--frames"), three letters or more. Ties go to the earlier candidate.
inline std::string closest_name(const std::string& word, const std::vector<std::string>& candidates) {
  std::string best;
  size_t best_distance = std::max<size_t>(1, word.size() / 3) + 1;
  for (const std::string& candidate : candidates) {
    if (candidate.empty() || candidate == word) continue;
    size_t distance = edit_distance(word, candidate);
    const size_t shorter = std::min(word.size(), candidate.size());
    const bool prefix = shorter >= 3 && word.compare(0, shorter, candidate, 0, shorter) == 0;
    // A prefix counts as one edit more than the closest typo could be.
    if (prefix) distance = std::min(distance, std::max<size_t>(1, word.size() / 3));
    if (distance < best_distance) {
      best = candidate;
      best_distance = distance;
    }
  }
  return best;
}

// "; did you mean X?" for an error message, or "" when nothing is close.
inline std::string did_you_mean(const std::string& word, const std::vector<std::string>& candidates) {
  const std::string closest = closest_name(word, candidates);
  return closest.empty() ? "" : "; did you mean " + closest + "?";
}

}  // namespace oit
