#include "search/global_search.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <random>

#include "core/stopwatch.hpp"
#include "model/particle.hpp"
#include "philox.h"
#include "search/rotation_set.hpp"

namespace depthtrack::search {

namespace {
// Philox stream of the search's perturbations (cl/philox.h lists every stream).
constexpr dt_u32 kSearchStream = DT_STREAM_SEARCH;

// The pose that puts the object's centre at `centre` (camera frame) with rotation q.
Pose centred_pose(const Eigen::Quaterniond& q, const Eigen::Vector3d& centre, const SearchObject& object) {
  return Pose(centre - q * object.centre, q);
}

// How far in front of its centre the object's surface reaches along the view axis when rotated by
// q, times 2/3: a measured point lies on the front surface, the centre behind it (2/3 is the mean
// over a sphere's visible disc).
double centre_offset(const Eigen::Quaterniond& q, const SearchObject& object) {
  const Eigen::Matrix3d r = q.toRotationMatrix();
  double front = 0;
  for (const auto& v : object.vertices) front = std::max(front, -(r.row(2).dot(v - object.centre)));
  return 2.0 / 3.0 * front;
}

// Candidates best first, skipping any within both `metres` (centres) and `radians` of a kept one.
std::vector<Candidate> best_distinct(std::vector<Candidate> all, size_t keep, const SearchObject& object, double metres,
                                     double radians) {
  std::sort(all.begin(), all.end(), [](const Candidate& a, const Candidate& b) { return a.score > b.score; });
  std::vector<Candidate> kept;
  for (const Candidate& c : all) {
    if (kept.size() >= keep) break;
    const Eigen::Vector3d centre = c.pose.apply(object.centre);
    const bool near = std::any_of(kept.begin(), kept.end(), [&](const Candidate& k) {
      return (k.pose.apply(object.centre) - centre).norm() < metres && rotation_error(k.pose, c.pose) < radians;
    });
    if (!near) kept.push_back(c);
  }
  return kept;
}

// Each surface point's region: the cube of edge `cell` (the object's radius) it falls in, numbered
// densely in the order first met.
std::vector<size_t> regions_of(std::span<const Eigen::Vector3d> surface, double cell, size_t& count) {
  std::map<std::array<long, 3>, size_t> index;
  std::vector<size_t> out(surface.size());
  for (size_t i = 0; i < surface.size(); ++i) {
    const std::array<long, 3> key{std::lround(std::floor(surface[i].x() / cell)),
                                  std::lround(std::floor(surface[i].y() / cell)),
                                  std::lround(std::floor(surface[i].z() / cell))};
    out[i] = index.emplace(key, index.size()).first->second;
  }
  count = index.size();
  return out;
}

std::vector<Candidate> scored(std::vector<Pose> poses, const ScoreFunction& score) {
  const std::vector<double> s = score(poses);
  std::vector<Candidate> out(poses.size());
  for (size_t i = 0; i < poses.size(); ++i) out[i] = {poses[i], s[i]};
  return out;
}
}  // namespace

double agreement_floor(std::span<const double> agreement, double margin) {
  if (agreement.empty()) return -std::numeric_limits<double>::infinity();
  return *std::max_element(agreement.begin(), agreement.end()) - margin;
}

void lower_disagreeing(std::span<double> scores, std::span<const double> agreement, double floor) {
  for (size_t i = 0; i < scores.size(); ++i)
    if (agreement[i] < floor) scores[i] -= kDisagrees;
}

ScoreFunction gated(ScoreFunction score, AgreementFunction agreement, double floor) {
  if (!agreement) return score;
  return [score = std::move(score), agreement = std::move(agreement), floor](std::span<const Pose> poses) {
    std::vector<double> out = score(poses);
    lower_disagreeing(out, agreement(poses), floor);
    return out;
  };
}

std::vector<Pose> poses_of(std::span<const Candidate> candidates) {
  std::vector<Pose> poses;
  poses.reserve(candidates.size());
  for (const Candidate& c : candidates) poses.push_back(c.pose);
  return poses;
}

std::vector<Candidate> refine_candidates(std::vector<Candidate> candidates, const SearchObject& object,
                                         const ScoreFunction& score, std::span<const RefineStage> stages,
                                         const SearchSettings& settings, size_t* poses_scored) {
  const size_t per = static_cast<size_t>(std::max(settings.perturbations, 0));
  for (size_t s = 0; s < stages.size() && !candidates.empty(); ++s) {
    const RefineStage& stage = stages[s];
    std::vector<Pose> poses;
    poses.reserve(candidates.size() * per);
    for (size_t c = 0; c < candidates.size(); ++c)
      for (size_t m = 0; m < per; ++m) {
        float n[6];
        dt_normals6(settings.seed, static_cast<dt_u32>(c * per + m), settings.round * 64u + static_cast<dt_u32>(s),
                    kSearchStream, n);
        poses.push_back(model::move_about_centre(candidates[c].pose, object.centre,
                                                 stage.metres * Eigen::Vector3d(n[0], n[1], n[2]),
                                                 stage.radians * Eigen::Vector3d(n[3], n[4], n[5])));
      }
    std::vector<Candidate> all = scored(std::move(poses), score);
    if (poses_scored) *poses_scored += all.size();
    all.insert(all.end(), candidates.begin(), candidates.end());  // a candidate survives unless beaten
    candidates = best_distinct(std::move(all), stage.keep, object, 2 * stage.metres, 2 * stage.radians);
  }
  return candidates;
}

GridResolution grid_resolution(const SearchObject& object, const Camera& camera,
                               std::span<const Eigen::Vector3d> surface, const SearchSettings& settings) {
  if (surface.empty()) return {};
  // One working pixel is metres_per_pixel at the surface's nearer depths (the first quartile: an
  // object stands in front of what is behind it), and turns the farthest vertex by
  // radians_per_pixel.
  std::vector<double> depths(surface.size());
  for (size_t i = 0; i < surface.size(); ++i) depths[i] = surface[i].z();
  std::nth_element(depths.begin(), depths.begin() + static_cast<std::ptrdiff_t>(depths.size() / 4), depths.end());
  const double metres_per_pixel = depths[depths.size() / 4] / camera.fx;
  const double radians_per_pixel = metres_per_pixel / std::max(object.radius, 1e-3);
  return {std::clamp(settings.coarse_pixels * radians_per_pixel, 0.15, 0.4), settings.coarse_pixels * metres_per_pixel};
}

SearchResult global_search(const SearchObject& object, const Camera& camera, std::span<const Eigen::Vector3d> surface,
                           const ScoreFunction& score, const SearchSettings& settings,
                           const AgreementFunction& agreement) {
  const Stopwatch clock;
  SearchResult result;
  if (surface.empty()) return result;
  const GridResolution grid = grid_resolution(object, camera, surface, settings);
  result.rotation_radius = grid.rotation_radius;
  result.translation_spacing = grid.translation_spacing;
  const double metres_per_pixel = grid.translation_spacing / settings.coarse_pixels;

  const std::vector<Eigen::Quaterniond> rotations = uniform_rotations(rotations_for_radius(result.rotation_radius));
  std::vector<double> offsets(rotations.size());
  for (size_t j = 0; j < rotations.size(); ++j) offsets[j] = centre_offset(rotations[j], object);

  size_t region_count = 1;
  const std::vector<size_t> region = settings.by_region
                                         ? regions_of(surface, std::max(object.radius, 1e-3), region_count)
                                         : std::vector<size_t>(surface.size(), 0);
  std::vector<std::vector<Candidate>> by_region(region_count);
  std::vector<std::vector<double>> region_agreement(region_count);  // of by_region's candidates, with agreement
  // Scores (surface point, rotation) pairs, numbered point * set.size() + rotation, in chunks; under a
  // budget, stops when its coarse share is spent. Returns the scores of those it reached, and their
  // agreement into `agreed` (with an agreement function).
  const auto score_pairs = [&](std::span<const size_t> pairs, std::span<const Eigen::Quaterniond> set,
                               std::span<const double> set_offsets, std::vector<double>* agreed) {
    const size_t chunk = 2048;
    std::vector<double> out;
    for (size_t first = 0; first < pairs.size(); first += chunk) {
      if (settings.budget_ms > 0 && first > 0 && clock.elapsed_ms() > 0.7 * settings.budget_ms) break;
      const size_t last = std::min(pairs.size(), first + chunk);
      std::vector<Pose> poses;
      for (size_t k = first; k < last; ++k) {
        const size_t i = pairs[k] / set.size(), j = pairs[k] % set.size();
        const Eigen::Vector3d ray = surface[i].normalized();
        poses.push_back(centred_pose(set[j], surface[i] + set_offsets[j] * ray, object));
      }
      const std::vector<double> a = agreement ? agreement(poses) : std::vector<double>();
      const std::vector<Candidate> part = scored(std::move(poses), score);
      for (size_t k = first; k < last; ++k) {
        const size_t r = region[pairs[k] / set.size()];
        by_region[r].push_back(part[k - first]);
        out.push_back(part[k - first].score);
        if (agreement) {
          region_agreement[r].push_back(a[k - first]);
          if (agreed) agreed->push_back(a[k - first]);
        }
      }
      result.coarse_poses += part.size();
    }
    return out;
  };
  const size_t sparse_count = rotations_for_radius(settings.sparse_radius);
  if (settings.two_level && settings.budget_ms <= 0 && 2 * sparse_count < rotations.size()) {
    // The sparse set first; then each point's grid rotations whose nearest sparse rotation was among
    // the best pairs.
    const std::vector<Eigen::Quaterniond> sparse = uniform_rotations(sparse_count);
    std::vector<double> sparse_offsets(sparse.size());
    for (size_t j = 0; j < sparse.size(); ++j) sparse_offsets[j] = centre_offset(sparse[j], object);
    std::vector<size_t> pairs(surface.size() * sparse.size());
    std::iota(pairs.begin(), pairs.end(), size_t{0});
    std::vector<double> sparse_agreement;
    std::vector<double> first = score_pairs(pairs, sparse, sparse_offsets, &sparse_agreement);
    // The best pairs among those that agree (the sparse set's own best agreement sets the floor).
    if (agreement)
      lower_disagreeing(first, sparse_agreement, agreement_floor(sparse_agreement, settings.agreement_margin));
    const size_t best =
        std::clamp(static_cast<size_t>(std::ceil(settings.sparse_share * static_cast<double>(pairs.size()))), size_t{1},
                   pairs.size());
    std::vector<size_t> rank(pairs.size());
    std::iota(rank.begin(), rank.end(), size_t{0});
    std::nth_element(rank.begin(), rank.begin() + static_cast<std::ptrdiff_t>(best - 1), rank.end(),
                     [&](size_t a, size_t b) { return first[a] > first[b]; });
    std::vector<char> chosen(pairs.size(), 0);
    for (size_t k = 0; k < best; ++k) chosen[rank[k]] = 1;
    std::vector<size_t> nearest(rotations.size());
    for (size_t j = 0; j < rotations.size(); ++j) {
      double closest = -1;
      for (size_t s = 0; s < sparse.size(); ++s) {
        const double d = std::abs(rotations[j].dot(sparse[s]));
        if (d > closest) closest = d, nearest[j] = s;
      }
    }
    std::vector<size_t> fine;
    for (size_t i = 0; i < surface.size(); ++i)
      for (size_t j = 0; j < rotations.size(); ++j)
        if (chosen[i * sparse.size() + nearest[j]]) fine.push_back(i * rotations.size() + j);
    score_pairs(fine, rotations, offsets, nullptr);
  } else {
    // Every pair; under a budget, in a shuffled order, so that the part scored in time covers the whole
    // grid evenly.
    std::vector<size_t> order(surface.size() * rotations.size());
    std::iota(order.begin(), order.end(), size_t{0});
    if (settings.budget_ms > 0) {
      std::mt19937_64 rng(settings.seed * 1000003u + settings.round);
      std::shuffle(order.begin(), order.end(), rng);
    }
    score_pairs(order, rotations, offsets, nullptr);
  }
  result.poses_scored = result.coarse_poses;
  // With an agreement: the grid's poses that disagree rank below every one that agrees, in every region.
  double floor = -std::numeric_limits<double>::infinity();
  if (agreement) {
    std::vector<double> all;
    for (const auto& a : region_agreement) all.insert(all.end(), a.begin(), a.end());
    floor = agreement_floor(all, settings.agreement_margin);
    for (size_t r = 0; r < region_count; ++r)
      for (size_t k = 0; k < by_region[r].size(); ++k)
        if (region_agreement[r][k] < floor) by_region[r][k].score -= kDisagrees;
  }
  const ScoreFunction refine_score = gated(score, agreement, floor);

  // The best regions by their best coarse score; each keeps its best distinct candidates.
  std::vector<size_t> ranked;
  for (size_t r = 0; r < region_count; ++r)
    if (!by_region[r].empty()) ranked.push_back(r);
  const auto best_of = [&](size_t r) {
    return std::max_element(by_region[r].begin(), by_region[r].end(),
                            [](const Candidate& a, const Candidate& b) { return a.score < b.score; })
        ->score;
  };
  std::vector<double> region_best(region_count, 0);
  for (size_t r : ranked) region_best[r] = best_of(r);
  std::sort(ranked.begin(), ranked.end(), [&](size_t a, size_t b) { return region_best[a] > region_best[b]; });
  ranked.resize(std::min(ranked.size(), static_cast<size_t>(std::max(settings.regions, 1))));
  if (ranked.empty()) return result;
  const size_t keep = std::max(static_cast<size_t>(std::max(settings.per_region, 1)),
                               (static_cast<size_t>(std::max(settings.keep, 1)) + ranked.size() - 1) / ranked.size());

  // Halve the steps each stage down to finest_pixels; each region's candidates thin out towards the
  // end, but no region's are compared with another's (the full model ranks them afterwards).
  std::vector<RefineStage> stages;
  double radians = 0.5 * result.rotation_radius, metres = 0.5 * result.translation_spacing;
  const double finest = settings.finest_pixels * metres_per_pixel;
  for (size_t k = keep; metres > finest; metres *= 0.5, radians *= 0.5) {
    stages.push_back({radians, metres, k});
    k = std::max<size_t>(settings.by_region ? 2 : 4, k / 2);
  }
  for (size_t r : ranked) {
    std::vector<Candidate> kept = best_distinct(std::move(by_region[r]), keep, object, 1.5 * result.translation_spacing,
                                                1.5 * result.rotation_radius);
    kept = refine_candidates(std::move(kept), object, refine_score, stages, settings, &result.poses_scored);
    result.candidates.insert(result.candidates.end(), kept.begin(), kept.end());
  }
  std::sort(result.candidates.begin(), result.candidates.end(),
            [](const Candidate& a, const Candidate& b) { return a.score > b.score; });
  return result;
}

}  // namespace depthtrack::search
