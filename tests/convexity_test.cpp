// Edge classification, paper Appendix A.2: CC (eq. 1), theta (eq. 2), the sigmoid
// threshold (eq. 3), SC (eq. 4) and their conjunction (eq. 5). Every expectation below is
// worked out by hand in the comment beside it.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "lccp/config.hpp"
#include "lccp/core/convexity.hpp"
#include "test_clouds.hpp"

namespace lccp {
namespace {

using test::deg2rad;

Patch patch(double x, double y, double z, double nx, double ny, double nz) {
  Eigen::Vector3d n(nx, ny, nz);
  n.normalize();
  return Patch{Eigen::Vector3f(float(x), float(y), float(z)), n.cast<float>()};
}

// beta 10, SC on, 60 / 25 / 0.25; PCL's smoothness check and the corner check (beyond the paper) off
ConvexityConfig paper_config() {
  ConvexityConfig config;
  config.smoothness_check = false;
  config.corner_check = false;
  return config;
}
constexpr PatchSizes kP1Sizes{0.005f, 0.02f};                  // v and s of P1

// --- eq. (1): convexity criterion -------------------------------------------------------

TEST(ConvexityCriterion, OutsideBoxEdgeIsConvex) {
  // A box occupying x < 0, z < 0. p1 on its top face (normal +z), p2 on its side face
  // (normal +x). d = x1 - x2 = (-0.01, 0, 0.01), d_hat = (-1, 0, 1)/sqrt2,
  // n1 - n2 = (-1, 0, 1): (n1 - n2) . d_hat = sqrt2 > 0 -> convex. beta = 90 deg.
  const Patch p1 = patch(-0.01, 0, 0, 0, 0, 1);
  const Patch p2 = patch(0, 0, -0.01, 1, 0, 0);
  const ConvexityConfig cfg = paper_config();
  EXPECT_NEAR(normal_angle_deg(p1, p2), 90.0f, 1e-4f);
  EXPECT_TRUE(convexity_criterion(p1, p2, cfg));
  // s = n1 x n2 = (0, 1, 0) is orthogonal to d: theta = 90 > theta_thresh(90) ~ 60.
  EXPECT_NEAR(sanity_angle_deg(p1, p2), 90.0f, 1e-3f);
  EXPECT_TRUE(sanity_criterion(p1, p2, cfg));
  EXPECT_TRUE(is_convex(p1, p2, cfg));
  // The bias cannot matter here: even with beta_thresh 0 it stays convex.
  ConvexityConfig no_bias = cfg;
  no_bias.beta_thresh_deg = 0.0f;
  EXPECT_TRUE(convexity_criterion(p1, p2, no_bias));
}

TEST(ConvexityCriterion, InsideCornerIsConcave) {
  // Floor z = 0 (normal +z) meeting a wall x = 0 (normal +x), free space x > 0, z > 0.
  // d = x1 - x2 = (0.01, 0, -0.01), d_hat = (1, 0, -1)/sqrt2, n1 - n2 = (-1, 0, 1):
  // (n1 - n2) . d_hat = -sqrt2 < 0 and beta = 90 >= 10 -> CC false.
  const Patch floor = patch(0.01, 0, 0, 0, 0, 1);
  const Patch wall = patch(0, 0, 0.01, 1, 0, 0);
  const ConvexityConfig cfg = paper_config();
  EXPECT_FALSE(convexity_criterion(floor, wall, cfg));
  EXPECT_FALSE(is_convex(floor, wall, cfg));
  // A bias above 90 deg turns it convex (the robot setting of the paper uses 180).
  ConvexityConfig merge_all = cfg;
  merge_all.beta_thresh_deg = 100.0f;
  EXPECT_TRUE(convexity_criterion(floor, wall, merge_all));
}

TEST(ConvexityCriterion, ShallowConcavityBelowBetaThreshIsConvex) {
  // A shallow valley: p2 on the flat floor z = 0 (x < 0), p1 on the side rising at 5 deg,
  // z = x tan5, with normal (-sin5, 0, cos5). d = (0.02, 0, 0.01 tan5),
  // (n1 - n2) . d = -0.02 sin5 + 0.01 tan5 (cos5 - 1) < 0 -> concave, but
  // beta = 5 deg < beta_thresh = 10 deg -> CC true (the bias of eq. 1).
  const double a = deg2rad(5.0);
  const Patch p1 = patch(0.01, 0, 0.01 * std::tan(a), -std::sin(a), 0, std::cos(a));
  const Patch p2 = patch(-0.01, 0, 0, 0, 0, 1);
  ConvexityConfig cfg = paper_config();
  EXPECT_NEAR(normal_angle_deg(p1, p2), 5.0f, 1e-3f);
  EXPECT_TRUE(convexity_criterion(p1, p2, cfg));
  // s = n1 x n2 is along y, d lies in the xz-plane: theta = 90 -> SC true, conv true.
  EXPECT_TRUE(is_convex(p1, p2, cfg));
  // Without enough bias the concavity shows: beta_thresh 4 deg < beta = 5 deg.
  cfg.beta_thresh_deg = 4.0f;
  EXPECT_FALSE(convexity_criterion(p1, p2, cfg));
  EXPECT_FALSE(is_convex(p1, p2, cfg));
}

TEST(ConvexityCriterion, CoplanarPairIsConvexAndSane) {
  // Same normal, centroids in the plane: (n1 - n2) . d = 0 (not > 0), beta = 0 < 10 -> CC
  // true by the bias alone. n1 x n2 = 0: no singular configuration, theta := 90.
  const Patch p1 = patch(0, 0, 1, 0, 0, -1);
  const Patch p2 = patch(0.02, 0.01, 1, 0, 0, -1);
  ConvexityConfig cfg = paper_config();
  EXPECT_NEAR(normal_angle_deg(p1, p2), 0.0f, 1e-3f);
  EXPECT_FLOAT_EQ(sanity_angle_deg(p1, p2), 90.0f);
  EXPECT_TRUE(convexity_criterion(p1, p2, cfg));
  EXPECT_TRUE(sanity_criterion(p1, p2, cfg));
  EXPECT_TRUE(is_convex(p1, p2, cfg));
  // Eq. (1) is strict on both sides: with beta_thresh = 0, beta = 0 is not < 0 and the
  // dot product 0 is not > 0.
  cfg.beta_thresh_deg = 0.0f;
  EXPECT_FALSE(convexity_criterion(p1, p2, cfg));
}

// --- eq. (2)-(4): sanity criterion ------------------------------------------------------

TEST(SanityCriterion, SingularSideBySidePairIsInvalid) {
  // A roof ridge along the y-axis: plane 1 is z = 0 (normal n1 = +z) for x < 0, plane 2
  // has normal n2 = (sin40, 0, cos40) (z = -x tan40) for x > 0; beta = 40 deg.
  // s = n1 x n2 = (0, sin40, 0) -- the ridge. The patches are slid along the ridge so that
  // d = x1 - x2 = (-0.002, 0.02, 0.001 tan40) is almost parallel to s (Fig. 6 C):
  //   theta = acos(0.02 / |d|) = 6.18 deg < theta_thresh(40) = 60/(1+exp(-3.75)) = 58.6 deg
  //   -> SC false. CC: (n1 - n2) . d = 0.002 sin40 + 0.001 tan40 (1 - cos40) > 0 -> true.
  const double b = deg2rad(40.0);
  const Eigen::Vector3d x1(-0.001, 0.01, 0.0);
  const Eigen::Vector3d x2(0.001, -0.01, -0.001 * std::tan(b));
  const Eigen::Vector3d n1(0, 0, 1), n2(std::sin(b), 0, std::cos(b));
  const Patch p1{x1.cast<float>(), n1.cast<float>()};
  const Patch p2{x2.cast<float>(), n2.cast<float>()};
  const Eigen::Vector3d d = x1 - x2;
  const double theta = test::rad2deg(std::acos(std::abs(d.normalized().dot(Eigen::Vector3d::UnitY()))));
  ASSERT_NEAR(theta, 6.18, 0.01);  // the hand value above

  ConvexityConfig cfg = paper_config();
  EXPECT_NEAR(normal_angle_deg(p1, p2), 40.0f, 1e-3f);
  EXPECT_NEAR(sanity_angle_deg(p1, p2), float(theta), 1e-2f);
  EXPECT_NEAR(sanity_threshold_deg(40.0f, cfg), float(60.0 / (1.0 + std::exp(-0.25 * 15.0))), 1e-4f);
  EXPECT_TRUE(convexity_criterion(p1, p2, cfg));
  EXPECT_FALSE(sanity_criterion(p1, p2, cfg));
  EXPECT_FALSE(is_convex(p1, p2, cfg));

  // With SC disabled, eq. (5) reduces to CC.
  cfg.sanity_criterion = false;
  EXPECT_TRUE(is_convex(p1, p2, cfg));
}

TEST(SanityCriterion, SameRidgeSharingItsBoundaryIsValid) {
  // The ridge above with the patches side by side across it: d = (-0.02, 0, 0.01 tan40)
  // is orthogonal to s = (0, sin40, 0): theta = 90 > 58.6 -> SC true; CC true -> convex.
  const double b = deg2rad(40.0);
  const Patch p1 = patch(-0.01, 0, 0, 0, 0, 1);
  const Patch p2 = patch(0.01, 0, -0.01 * std::tan(b), std::sin(b), 0, std::cos(b));
  const ConvexityConfig cfg = paper_config();
  EXPECT_NEAR(sanity_angle_deg(p1, p2), 90.0f, 1e-3f);
  EXPECT_TRUE(sanity_criterion(p1, p2, cfg));
  EXPECT_TRUE(is_convex(p1, p2, cfg));
}

TEST(SanityCriterion, ThresholdIsStrictAroundTheSigmoidMidpoint) {
  // beta = 25 deg = beta_off, so theta_thresh = 60 / 2 = 30 deg. n1 = +z,
  // n2 = (sin25, 0, cos25), s along +y. d at angle theta from the y-axis in the xy-plane.
  const double b = deg2rad(25.0);
  const Eigen::Vector3f n1(0, 0, 1);
  const Eigen::Vector3f n2 = Eigen::Vector3d(std::sin(b), 0, std::cos(b)).cast<float>();
  const ConvexityConfig cfg = paper_config();
  for (double theta : {35.0, 25.0, 31.0, 29.0, 60.0, 5.0}) {
    SCOPED_TRACE(theta);
    const double t = deg2rad(theta);
    const Patch p1{Eigen::Vector3f(0, 0, 1), n1};
    const Patch p2{(Eigen::Vector3d(0, 0, 1) - 0.02 * Eigen::Vector3d(-std::sin(t), std::cos(t), 0)).cast<float>(), n2};
    EXPECT_NEAR(sanity_angle_deg(p1, p2), float(theta), 1e-2f);
    EXPECT_EQ(sanity_criterion(p1, p2, cfg), theta > 30.0);
  }
}

TEST(SanityThreshold, SigmoidValues) {
  const ConvexityConfig cfg = paper_config();
  // Eq. (3) at beta = beta_off: 60 / (1 + exp(0)) = 30 exactly.
  EXPECT_NEAR(sanity_threshold_deg(25.0f, cfg), 30.0f, 1e-5f);
  // beta = 0: 60 / (1 + exp(0.25 * 25)) = 60 / (1 + e^6.25) = 0.11560...
  EXPECT_NEAR(sanity_threshold_deg(0.0f, cfg), 60.0 / (1.0 + std::exp(6.25)), 1e-5);
  EXPECT_NEAR(sanity_threshold_deg(0.0f, cfg), 0.11560f, 1e-4f);
  // Large beta saturates at theta_max.
  EXPECT_NEAR(sanity_threshold_deg(90.0f, cfg), 60.0f, 1e-4f);
  EXPECT_NEAR(sanity_threshold_deg(180.0f, cfg), 60.0f, 1e-5f);
  // Monotone: strictly increasing while the sigmoid has not saturated in float (up to
  // 70 deg the step to the next degree, ~60 a e^-a(beta-25) >= 2e-4, is far above the
  // float spacing at 60, 3.8e-6), non-decreasing beyond (from ~176 deg it is exactly 60).
  float prev = sanity_threshold_deg(0.0f, cfg);
  for (int beta = 1; beta <= 180; ++beta) {
    const float cur = sanity_threshold_deg(float(beta), cfg);
    if (beta <= 70) {
      EXPECT_GT(cur, prev) << "beta " << beta;
    } else {
      EXPECT_GE(cur, prev) << "beta " << beta;
    }
    prev = cur;
  }
  // The config fields are used: theta_max 40, beta_off 10, a 0.5 at beta 12:
  // 40 / (1 + exp(-0.5 * 2)) = 40 / (1 + e^-1) = 29.2423...
  ConvexityConfig other = cfg;
  other.theta_max_deg = 40.0f;
  other.beta_off_deg = 10.0f;
  other.sigmoid_slope_per_deg = 0.5f;
  EXPECT_NEAR(sanity_threshold_deg(12.0f, other), 40.0 / (1.0 + std::exp(-1.0)), 1e-4);
}

TEST(NormalAngle, KnownAngles) {
  const Patch a = patch(0, 0, 1, 0, 0, 1);
  EXPECT_NEAR(normal_angle_deg(a, patch(0.01, 0, 1, 1, 0, 0)), 90.0f, 1e-4f);
  EXPECT_NEAR(normal_angle_deg(a, patch(0.01, 0, 1, 0, -1, 0)), 90.0f, 1e-4f);
  const double t = deg2rad(60.0);
  EXPECT_NEAR(normal_angle_deg(a, patch(0.01, 0, 1, std::sin(t), 0, std::cos(t))), 60.0f, 1e-3f);
  EXPECT_NEAR(normal_angle_deg(a, a), 0.0f, 1e-3f);
}

// --- symmetry: the paper notes all criteria are commutative -----------------------------

TEST(ConvexitySymmetry, SwappingPatchesNeverChangesTheDecision) {
  std::mt19937 rng(12345);
  std::normal_distribution<float> gauss(0.0f, 1.0f);
  std::uniform_real_distribution<float> uni(-0.05f, 0.05f);
  auto random_unit = [&] {
    Eigen::Vector3f v(gauss(rng), gauss(rng), gauss(rng));
    return Eigen::Vector3f(v.normalized());
  };
  ConvexityConfig cfg = paper_config();
  int convex = 0, cc = 0, sc = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    Patch p1{Eigen::Vector3f(uni(rng), uni(rng), 1.0f + uni(rng)), random_unit()};
    Eigen::Vector3f n2 = random_unit();
    if (i % 2 == 0) n2 = (p1.normal + 0.2f * random_unit()).normalized();  // many small betas too
    Patch p2{Eigen::Vector3f(uni(rng), uni(rng), 1.0f + uni(rng)), n2};
    cfg.sanity_criterion = (i % 3 != 0);
    ASSERT_EQ(convexity_criterion(p1, p2, cfg), convexity_criterion(p2, p1, cfg)) << "pair " << i;
    ASSERT_EQ(sanity_criterion(p1, p2, cfg), sanity_criterion(p2, p1, cfg)) << "pair " << i;
    ASSERT_EQ(is_convex(p1, p2, cfg), is_convex(p2, p1, cfg)) << "pair " << i;
    ASSERT_NEAR(normal_angle_deg(p1, p2), normal_angle_deg(p2, p1), 1e-4f);
    ASSERT_NEAR(sanity_angle_deg(p1, p2), sanity_angle_deg(p2, p1), 1e-3f);
    const float theta = sanity_angle_deg(p1, p2);
    ASSERT_GE(theta, 0.0f);
    ASSERT_LE(theta, 90.0f);
    convex += is_convex(p1, p2, cfg);
    cc += convexity_criterion(p1, p2, cfg);
    sc += sanity_criterion(p1, p2, cfg);
  }
  // The sample must exercise both outcomes of every predicate.
  EXPECT_GT(convex, n / 20);
  EXPECT_LT(convex, n - n / 20);
  EXPECT_GT(cc, n / 20);
  EXPECT_LT(cc, n - n / 20);
  EXPECT_GT(sc, n / 20);
  EXPECT_LT(sc, n - n / 20);
}

TEST(ConvexityDefinition, IsConvexIsCcAndSc) {
  // Eq. (5) on random pairs: conv == CC && SC with SC on, == CC with SC off.
  std::mt19937 rng(777);
  std::normal_distribution<float> gauss(0.0f, 1.0f);
  for (int i = 0; i < 5000; ++i) {
    Patch p1{Eigen::Vector3f(gauss(rng), gauss(rng), gauss(rng)) * 0.02f,
             Eigen::Vector3f(gauss(rng), gauss(rng), gauss(rng)).normalized()};
    Patch p2{Eigen::Vector3f(gauss(rng), gauss(rng), gauss(rng)) * 0.02f,
             Eigen::Vector3f(gauss(rng), gauss(rng), gauss(rng)).normalized()};
    ConvexityConfig cfg = paper_config();
    const bool cc = convexity_criterion(p1, p2, cfg), sc = sanity_criterion(p1, p2, cfg);
    ASSERT_EQ(is_convex(p1, p2, cfg), cc && sc) << "pair " << i;
    cfg.sanity_criterion = false;
    ASSERT_EQ(is_convex(p1, p2, cfg), cc) << "pair " << i;
  }
}

// --- classify_edges ----------------------------------------------------------------------

TEST(ClassifyEdges, MatchesIsConvexPerEdge) {
  // Six patches around the box of OutsideBoxEdgeIsConvex (box: x < 0, z < 0) and the
  // roof ridge of SingularSideBySidePairIsInvalid, worked out by hand:
  //   0: (-0.01, 0, 0)   n +z   top face
  //   1: (0, 0, -0.01)   n +x   side face
  //   2: (-0.001, 0.01, 0) n +z ridge side 1 (also on the top face plane)
  //   3: (0.001, -0.01, -0.001 tan40) n (sin40, 0, cos40)  ridge side 2
  //   4: (-0.03, 0, 0)   n +z   top face, farther in
  //   5: (0.01, 0, -0.02) n +z  the ground in front of the side face
  // (0,1): the outside box edge -> 1.
  // (0,3): d = (-0.011, 0.01, 0.00084), (n0 - n3) . d = 0.0073 > 0 -> CC; s along y,
  //        theta = acos(0.01 / 0.01489) = 47.8 < theta_thresh(40) = 58.6 -> SC false -> 0.
  // (0,4): coplanar -> CC by the bias, theta = 90 -> 1.
  // (1,2): d = (0.001, -0.01, -0.01), (n1 - n2) . d = 0.011 > 0 -> CC; s = (0, -1, 0),
  //        theta = acos(0.01 / 0.01418) = 45.1 < theta_thresh(90) = 60 -> SC false -> 0.
  // (1,4): d = (0.03, 0, -0.01), (n1 - n4) . d = 0.04 > 0 -> CC; s orthogonal to d -> 1.
  // (1,5): inside corner: d = (-0.01, 0, 0.01), (n1 - n5) . d = -0.02 < 0, beta 90 -> 0.
  // (2,3): the singular ridge pair -> 0.
  const double b = deg2rad(40.0);
  const std::vector<Eigen::Vector3f> c = {{-0.01f, 0, 0},
                                          {0, 0, -0.01f},
                                          {-0.001f, 0.01f, 0},
                                          Eigen::Vector3d(0.001, -0.01, -0.001 * std::tan(b)).cast<float>(),
                                          {-0.03f, 0, 0},
                                          {0.01f, 0, -0.02f}};
  const std::vector<Eigen::Vector3f> n = {
      {0, 0, 1}, {1, 0, 0}, {0, 0, 1}, Eigen::Vector3d(std::sin(b), 0, std::cos(b)).cast<float>(), {0, 0, 1}, {0, 0, 1}};
  const std::vector<Edge> edges = {{0, 1}, {0, 3}, {0, 4}, {1, 2}, {1, 4}, {1, 5}, {2, 3}};
  const std::vector<std::uint8_t> hand = {1, 0, 1, 0, 1, 0, 0};
  const ConvexityConfig cfg = paper_config();
  const auto flags = classify_edges(edges, c, n, cfg, kP1Sizes);
  ASSERT_EQ(flags.size(), edges.size());
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const Patch pa{c[edges[e].a], n[edges[e].a]}, pb{c[edges[e].b], n[edges[e].b]};
    EXPECT_EQ(flags[e], hand[e]) << "edge " << edges[e].a << "-" << edges[e].b;
    EXPECT_EQ(flags[e] != 0, is_convex(pa, pb, cfg)) << "edge " << edges[e].a << "-" << edges[e].b;
  }
  // With SC off, (0,3) and (1,2) and (2,3) follow CC: true, true, true.
  ConvexityConfig no_sc = cfg;
  no_sc.sanity_criterion = false;
  const auto flags2 = classify_edges(edges, c, n, no_sc, kP1Sizes);
  EXPECT_EQ(flags2, (std::vector<std::uint8_t>{1, 1, 1, 1, 1, 0, 1}));
}

TEST(ClassifyEdges, LargeRandomGraphMatchesIsConvex) {
  // Big enough to be split across threads.
  std::mt19937 rng(99);
  std::normal_distribution<float> gauss(0.0f, 1.0f);
  const std::uint32_t nodes = 3000;
  std::vector<Eigen::Vector3f> c(nodes), n(nodes);
  for (std::uint32_t i = 0; i < nodes; ++i) {
    c[i] = Eigen::Vector3f(gauss(rng), gauss(rng), gauss(rng)) * 0.05f + Eigen::Vector3f(0, 0, 1);
    n[i] = Eigen::Vector3f(gauss(rng), gauss(rng), gauss(rng) - 3.0f).normalized();
  }
  std::vector<Edge> edges;
  std::uniform_int_distribution<std::uint32_t> pick(0, nodes - 1);
  for (int k = 0; k < 20000; ++k) {
    std::uint32_t a = pick(rng), b = pick(rng);
    if (a == b) continue;
    if (a > b) std::swap(a, b);
    edges.push_back({a, b});
  }
  std::sort(edges.begin(), edges.end(), [](const Edge& x, const Edge& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; });
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  for (bool sanity : {true, false}) {
    ConvexityConfig cfg = paper_config();
    cfg.sanity_criterion = sanity;
    const auto flags = classify_edges(edges, c, n, cfg, kP1Sizes);
    ASSERT_EQ(flags.size(), edges.size());
    std::size_t ones = 0;
    for (std::size_t e = 0; e < edges.size(); ++e) {
      const bool expected = is_convex({c[edges[e].a], n[edges[e].a]}, {c[edges[e].b], n[edges[e].b]}, cfg);
      ASSERT_EQ(flags[e], expected ? 1 : 0) << "edge " << e;
      ones += flags[e];
    }
    EXPECT_GT(ones, 0u);
    EXPECT_LT(ones, edges.size());
  }
}

// --- PCL's smoothness check (beyond the paper) -------------------------------------------

TEST(SmoothnessCriterion, ParallelPatchesWithAStepAreCut) {
  // Two upward patches 2 cm apart in x, the second 1 mm lower: parallel normals explain no
  // offset (|n1 x n2| = 0), so the step of 1 mm is measured against the slack alone,
  // 0.1 v = 0.5 mm at P1: cut. A 0.4 mm step is within it.
  ConvexityConfig cfg = paper_config();
  cfg.smoothness_check = true;
  const Patch upper = patch(0, 0, 0, 0, 0, 1);
  EXPECT_NEAR(step_distance_m(upper, patch(0.02, 0, -0.001, 0, 0, 1)), 0.001f, 1e-6f);
  EXPECT_FALSE(smoothness_criterion(upper, patch(0.02, 0, -0.001, 0, 0, 1), cfg, kP1Sizes));
  EXPECT_TRUE(smoothness_criterion(upper, patch(0.02, 0, -0.0004, 0, 0, 1), cfg, kP1Sizes));
  // Both pass CC (beta 0 < 10) and SC (no intersection line): only the check cuts the step.
  EXPECT_TRUE(is_convex(upper, patch(0.02, 0, -0.001, 0, 0, 1), cfg));
  const std::vector<Eigen::Vector3f> c{{0, 0, 0}, {0.02f, 0, -0.001f}}, n{{0, 0, 1}, {0, 0, 1}};
  EXPECT_EQ(classify_edges({{0, 1}}, c, n, cfg, kP1Sizes), std::vector<std::uint8_t>{0});
  cfg.smoothness_check = false;
  EXPECT_EQ(classify_edges({{0, 1}}, c, n, cfg, kP1Sizes), std::vector<std::uint8_t>{1});
}

TEST(SmoothnessCriterion, TheAngleExplainsTheOffsetOfABentSurface) {
  // A ridge: p1 normal (0, 0, 1) at the origin, p2 tilted 30 deg about y, 1 cm along x
  // and 1 cm * tan(15 deg) lower (both patches tangent to one bent surface).
  // d = (-0.01, 0, 0.00268): |d . n1| = 2.68 mm; |d . n2| = |-0.01 sin30 + 0.00268 cos30|
  // = 2.68 mm. Allowed: |n1 x n2| s + 0.1 v = sin30 * 2 cm + 0.5 mm = 10.5 mm: smooth.
  ConvexityConfig cfg = paper_config();
  cfg.smoothness_check = true;
  const double t = deg2rad(30.0);
  const Patch p1 = patch(0, 0, 0, 0, 0, 1);
  const Patch p2 = patch(0.01, 0, -0.01 * std::tan(t / 2), std::sin(t), 0, std::cos(t));
  EXPECT_NEAR(step_distance_m(p1, p2), 0.00268f, 1e-5f);
  EXPECT_TRUE(smoothness_criterion(p1, p2, cfg, kP1Sizes));
  // p2 3 cm lower is a step no 30 deg bend over 2 cm explains: d = (-0.01, 0, 0.03),
  // |d . n1| = 30 mm, |d . n2| = |-0.005 + 0.03 cos30| = 20.98 mm > 10.5 mm.
  const Patch stepped = patch(0.01, 0, -0.03, std::sin(t), 0, std::cos(t));
  EXPECT_NEAR(step_distance_m(p1, stepped), 0.02098f, 1e-5f);
  EXPECT_FALSE(smoothness_criterion(p1, stepped, cfg, kP1Sizes));
  // The slack is in voxel sizes: threshold 3 at v = 5 mm allows 15 mm more, 25 mm in all.
  cfg.smoothness_threshold = 3.0f;
  EXPECT_TRUE(smoothness_criterion(p1, stepped, cfg, kP1Sizes));
}

// --- the corner check (beyond the paper) -------------------------------------------------

// Two patches whose normals are 120 deg apart, n1 = (-0.5, 0, 0.866) and n2 = (1, 0, 0);
// p2 at the origin. s = n1 x n2 = (0, 0.866, 0) and both d below have no y: theta = 90,
// SC holds. The slack is 0.1 v = 0.5 mm at P1 (no sensor step).
Patch limb() { return patch(0, 0, 0, 1, 0, 0); }
Patch sharp_patch(double x, double z) { return patch(x, 0, z, -0.5, 0, std::sqrt(3.0) / 2); }

// Eq. (1)'s measure, by hand: a box's convex edge (top face p1 at x = -1 cm facing
// +z, side face p2 1 cm below the edge facing +x): d_hat = (-1, 0, 1) / sqrt(2),
// (n1 - n2) . d_hat = ((-1, 0, 1) . (-1, 0, 1)) / sqrt(2) = sqrt(2). The same
// whichever patch is first; a wall rising from the top's edge (1 cm above it, facing -x,
// back over the top: a concave corner) gives -sqrt(2);
// two patches of one plane give 0. edge_convexity gives it per edge.
TEST(ConvexityMeasure, ConvexPositiveConcaveNegativeFlatZero) {
  const Patch top = patch(-0.01, 0, 0, 0, 0, 1), side = patch(0, 0, -0.01, 1, 0, 0);
  const Patch inner = patch(0, 0, 0.01, -1, 0, 0), beside = patch(-0.02, 0, 0, 0, 0, 1);
  EXPECT_NEAR(convexity_measure(top, side), std::sqrt(2.0f), 1e-5f);
  EXPECT_NEAR(convexity_measure(side, top), std::sqrt(2.0f), 1e-5f);
  EXPECT_NEAR(convexity_measure(top, inner), -std::sqrt(2.0f), 1e-5f);
  EXPECT_NEAR(convexity_measure(top, beside), 0.0f, 1e-6f);
  const std::vector<Eigen::Vector3f> centroids = {top.centroid, side.centroid, inner.centroid};
  const std::vector<Eigen::Vector3f> normals = {top.normal, side.normal, inner.normal};
  const std::vector<float> measure = edge_convexity({{0, 1}, {0, 2}}, centroids, normals);
  ASSERT_EQ(measure.size(), 2u);
  EXPECT_NEAR(measure[0], std::sqrt(2.0f), 1e-5f);
  EXPECT_NEAR(measure[1], -std::sqrt(2.0f), 1e-5f);
}

TEST(CornerCriterion, BothFacesOfASharpConvexWedgeLieBehindEachOther) {
  // A 60 deg wedge along y: p2's face runs from the edge down z, p1's from the edge
  // along (-0.866, 0, -0.5), each centroid 1 cm from it: x1 = (-0.00866, 0, -0.005),
  // x2 = (0, 0, -0.01). d = (-0.00866, 0, 0.005): d . n1 = 4.33 + 4.33 = 8.66 mm > -0.5 mm,
  // d . n2 = -8.66 mm < 0.5 mm: a corner. CC: (n1 - n2) . d = 8.66 + 8.66 mm > 0.
  ConvexityConfig cfg = paper_config();
  cfg.corner_check = true;
  const Patch p1 = sharp_patch(-0.01 * std::sqrt(3.0) / 2, -0.005), p2 = patch(0, 0, -0.01, 1, 0, 0);
  EXPECT_NEAR(normal_angle_deg(p1, p2), 120.0f, 1e-3f);
  EXPECT_TRUE(is_convex(p1, p2, cfg));
  EXPECT_TRUE(corner_criterion(p1, p2, cfg, kP1Sizes));
  EXPECT_TRUE(corner_criterion(p2, p1, cfg, kP1Sizes));
}

TEST(CornerCriterion, APatchPassingInFrontOfAnotherIsNoCorner) {
  // p1 8 mm in front of p2's plane and 16 mm along z: d = (0.008, 0, 0.016), d . n2 = 8 mm,
  // d . n1 = -0.004 + 0.013856 = 9.856 mm. Eq. (1): (n1 - n2) . d = 1.856 mm > 0, convex,
  // and the step, min(9.856, 8) = 8 mm, is within |n1 x n2| s = 0.866 * 2 cm = 17.3 mm:
  // smooth. Only the corner check cuts it: x1 lies 8 mm in front of p2's plane.
  ConvexityConfig cfg = paper_config();
  cfg.smoothness_check = true;
  const Patch p1 = sharp_patch(0.008, 0.016), p2 = limb();
  EXPECT_TRUE(is_convex(p1, p2, cfg));
  EXPECT_TRUE(smoothness_criterion(p1, p2, cfg, kP1Sizes));
  EXPECT_FALSE(corner_criterion(p1, p2, cfg, kP1Sizes));
  EXPECT_FALSE(corner_criterion(p2, p1, cfg, kP1Sizes));
  const std::vector<Eigen::Vector3f> c{p1.centroid, p2.centroid}, n{p1.normal, p2.normal};
  EXPECT_EQ(classify_edges({{0, 1}}, c, n, cfg, kP1Sizes), std::vector<std::uint8_t>{1});
  cfg.corner_check = true;
  EXPECT_EQ(classify_edges({{0, 1}}, c, n, cfg, kP1Sizes), std::vector<std::uint8_t>{0});
  // 0.4 mm in front (within the slack) is a corner: d = (0.0004, 0, 0.016).
  EXPECT_TRUE(corner_criterion(sharp_patch(0.0004, 0.016), p2, cfg, kP1Sizes));
}

TEST(CornerCriterion, EdgesLessSharpThanARightAngleAreNotAsked) {
  // n1 = (0, 0, 1), n2 tilted 60 deg from it (normals 60 deg apart), p1 far in front of
  // p2's plane: the check leaves it to eq. (1)-(5).
  ConvexityConfig cfg = paper_config();
  cfg.corner_check = true;
  const double t = deg2rad(60.0);
  EXPECT_TRUE(corner_criterion(patch(0, 0, 0.05, 0, 0, 1), patch(0, 0, 0, std::sin(t), 0, std::cos(t)), cfg, kP1Sizes));
}

TEST(ClassifyEdges, EmptyEdgeList) {
  const auto flags = classify_edges({}, {}, {}, paper_config(), kP1Sizes);
  EXPECT_TRUE(flags.empty());
}

}  // namespace
}  // namespace lccp
