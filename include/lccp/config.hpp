#pragma once
// Parameters of the LCCP method. Defaults are the paper's parameter set P1
// (Table II, beta_thresh 10 deg); every field carries its unit in its name.
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>

namespace lccp {

// How points are binned into voxels.
enum class Binning {
  automatic,  // camera if every point lies in a camera's view from the origin (organized or not), euclidean otherwise
  euclidean,  // cubes of voxel_size_m in metres (the paper)
  camera,     // cells of voxel_size_m in (x/z, y/z, ln z): size grows with depth (PCL)
  organized,  // PCL's rule: camera for an organized cloud in front of the sensor, euclidean otherwise
};

struct VoxelConfig {
  float voxel_size_m = 0.005f;  // v
  Binning binning = Binning::automatic;
};

// Voxel normals (stage 2). crease_preserving, beyond the paper (docs/ARCHITECTURE.md,
// departures): where a voxel's neighbourhood straddles a crease, the voxel takes
// the plane of the flattest neighbouring neighbourhood it lies on, so normals,
// and the supervoxels grown from them, do not blend two surfaces. It also
// erases faces narrower than the neighbourhood (two voxels), e.g. the 1 cm step
// between two touching boxes' parallel sides; the flood growth's plane test
// keeps the two sides in patches of their own, and the smoothness check
// (ConvexityConfig) cuts between them. Off in the paper.
//
// planar_variation: a voxel normal is a plane's when the neighbourhood it came
// from has at most this surface variation (least eigenvalue / trace, Pauly,
// Gross and Kobbelt 2002). 0.03 keeps 99 % of the voxels of flat surfaces
// planar (99th percentile 0.022, crease-preserving normals, real Kinect frames
// at 0.5-1.5 m). The flood growth's patches take their normal from their planar
// members (docs/ARCHITECTURE.md).
struct NormalConfig {
  bool crease_preserving = true;
  float planar_variation = 0.03f;
};

// How supervoxels grow from their seeds (stage 4).
enum class Growth {
  vccs,   // VCCS (Papon et al. 2013): int(1.8 s / v) - 1 synchronous flow passes, as the paper and PCL run it
  flood,  // beyond the paper: a priority flood settles each voxel once, never across a crease or a step
};

// depth_scaled_seeds, beyond the paper (docs/ARCHITECTURE.md, departures): camera
// cells grow with depth (side v z, z in metres) while VCCS's seed grid does not, so
// beyond z0 = s / (4 v) a seed cell spans fewer than the 4 voxels of the paper's
// finest patch (P1: s = 4 v), and from z = s / v on each voxel is a supervoxel of
// its own. With the key, seeds there are 4 camera cells apart (s z / z0) and
// growth measures distance in that spacing. Nearer than z0, and with cubic
// voxels, nothing changes. P1: z0 = 1 m; P2: 2 m.
//
// growth = flood, beyond the paper (docs/ARCHITECTURE.md, departures): the
// seeds' patches flood the voxel adjacency in order of the VCCS distance to
// the patch as it stands (seeded region growing), each voxel settled once,
// then one VCCS pass against the patches' means. A patch admits a voxel only
// within max_normal_angle_deg of its normal (a larger change is a crease) and
// within the sensor's depth noise of its plane (SensorConfig: a larger offset
// is a step, where two faces meet), so no patch straddles two surfaces.
struct SupervoxelConfig {
  Growth growth = Growth::flood;
  float seed_size_m = 0.02f;   // s: seed grid spacing
  bool depth_scaled_seeds = true;
  float spatial_weight = 1.0f; // w_s, per seed_size_m of distance
  float normal_weight = 4.0f;  // w_n, on 1 - |n1 . n2|
  float color_weight = 0.0f;   // w_c, on |rgb1 - rgb2| / 255
  // flood: 2.5 times the 99th percentile (12 deg) of the angle between a voxel
  // normal and its patch's on flat surfaces of real Kinect frames at 0.5-1.5 m.
  float max_normal_angle_deg = 30.0f;
};

// The depth sensor's noise, for the flood growth's plane test: a Kinect v1 by
// default. Depth is quantized in disparity steps of d pixels, so neighbouring
// measurable depths are z^2 d / (f b) apart (Khoshelham and Elberink 2012,
// "Accuracy and resolution of Kinect depth data", Sensors 12(2)); the axial
// noise's standard deviation is sigma0 + sigma2 (z - z_min)^2 (Nguyen, Izadi
// and Lovell 2012, "Modeling Kinect sensor noise"). A point is on a plane when
// it lies within one step and two standard deviations of it.
//
// depth_steps, beyond the paper (docs/ARCHITECTURE.md, departures): where the
// cloud is in the camera's frame (camera cells), depth differences below one
// step are not measured. A camera cell is v z deep, shallower than a step
// beyond z_q = v / q (q = d / (f b); Kinect v1, P1: 1.74 m; at 4.5 m 5.8 cm
// steps against 2.3 cm cells), so pixels one step apart fall in cells that
// are not adjacent and one slanted wall becomes terraces no adjacency joins.
// With the key a camera cell is never shallower than a step, and the
// smoothness check (ConvexityConfig) never takes an offset within half a step
// (the sensor's rounding) for a step between surfaces. Off in the paper.
struct SensorConfig {
  bool depth_steps = true;
  float focal_px = 580.0f;             // f, the disparity's focal length (pixels)
  float baseline_m = 0.075f;           // b, projector to camera
  float disparity_step_px = 0.125f;    // d, the disparity's quantization (1/8 pixel)
  float axial_sigma_m = 0.0012f;       // sigma0, at the nearest range
  float axial_sigma_per_m2 = 0.0019f;  // sigma2
  float min_range_m = 0.4f;            // z_min; nearer depths count as z_min

  // q z^2 with q = d / (f b): the step between neighbouring measurable depths (metres).
  float depth_step_m(float z_m) const { return z_m * z_m * disparity_step_px / (focal_px * baseline_m); }
  float step_per_m2() const { return disparity_step_px / (focal_px * baseline_m); }  // q (1/metre)
  // depth_step_m(z) + 2 (sigma0 + sigma2 (z - z_min)^2), z clamped to z_min from below (metres).
  float depth_tolerance_m(float z_m) const;
};

struct ConvexityConfig {
  float beta_thresh_deg = 10.0f;        // CC bias, eq. (1)
  bool sanity_criterion = true;         // SC, eq. (4)
  float theta_max_deg = 60.0f;          // eq. (3)
  float beta_off_deg = 25.0f;           // eq. (3)
  float sigmoid_slope_per_deg = 0.25f;  // a in eq. (3)
  // PCL's smoothness check, beyond the paper (pcl::LCCPSegmentation::
  // setSmoothnessCheck): an edge between two patches offset along their normals
  // by more than their angle explains (a step) is not convex. Off in the paper.
  bool smoothness_check = true;
  float smoothness_threshold = 0.1f;  // the step's slack, in voxel sizes v (PCL's default)
  // The corner check, beyond the paper: an edge whose normals are at least 90 deg
  // apart (a corner sharper than a box's edge) is convex only if each patch lies
  // behind the other's tangent plane, up to the smoothness check's slack, as both
  // faces of a convex corner do. Eq. (1) asks only that x1 lie less far in front
  // of plane 2 than x2 of plane 1; a patch passing in front of another's
  // silhouette (a mug's handle before the body's limb) meets that too. Off in the paper.
  bool corner_check = true;
};

// Support-plane removal before segmentation (paper Sec. III.C, Fig. 5: "an
// initial ground plane separation step"): RANSAC finds the dominant plane and
// its points become the support segment. Off in P1 and P2, on in the object preset.
struct SupportPlaneConfig {
  bool enabled = false;
  float distance_m = 0.01f;           // a point within this distance of the plane is on it
  float up_x = 0, up_y = 0, up_z = 0; // expected up direction (sensor frame); all 0: any plane
  float max_tilt_deg = 30.0f;         // largest angle between the plane normal and up (if up is set)
  float min_inlier_share = 0.1f;      // fewer inliers (share of finite points): no support plane
  std::uint32_t iterations = 256;     // RANSAC hypotheses
  std::uint32_t seed = 1;             // RANSAC random seed: fixed, so every run finds the same plane
  // Beyond the paper: a noise-scaled band. 0: every point within distance_m is
  // on the plane (the paper's band, which takes the lowest centimetre of every
  // object standing on it). k > 0: a point at depth z is on the plane within
  // k s z^2 of it, s z^2 the robust standard deviation of the plane's own
  // inliers' distances scaled as the Kinect's noise and depth step scale
  // (Khoshelham and Elberink 2012: both grow as z^2); never less than half
  // the sensor's depth step (its rounding), never more than distance_m.
  // 3: a Gaussian's 99.7 %, and a uniform rounding error's whole width.
  float noise_sigmas = 0.0f;
  // Beyond the paper: the band's points near other points are segmented with
  // them, and the patches decide. false: every band point is left out (the
  // paper's removal). true: a band point is left out only when no point off the
  // band lies in its cell or a neighbouring one of a grid of distance_m cells
  // (the open table); the others are segmented with the objects, and after the
  // filter (A.4) the support is the band regions (supervoxels most of whose
  // points are in the band, joined by edges) whose band points' mean height
  // agrees with the open table's in the cells around them (two seed spacings
  // wide; the plane itself where there is none) within half a depth step plus
  // three times the spread of the difference: its standard errors and the open
  // table's own flatness from cell to cell. A region that does not is a plane
  // of its own just above the support (a pan's floor). A band point of any
  // other supervoxel stays with it unless the support fits it at least as well
  // as its supervoxel's plane, the support taken where it is (the plane raised
  // by the open table's mean height in the point's cell and those around it):
  // an object keeps its foot, a neighbourhood planar with the support goes to
  // the support.
  bool decided_by_patches = false;
};

// The region of interest: an axis-aligned box in the cloud's frame (metres).
// Points outside it are left out before anything else and get label 0, as
// points without depth do; the support plane is sought among the rest. In a
// camera frame z is the depth along the optical axis, so min_z_m and max_z_m
// are a depth range. Default: all of space. (Like PCL's pcl::CropBox, and
// pcl::PassThrough on one axis.)
struct RegionConfig {
  static constexpr float kUnbounded = std::numeric_limits<float>::infinity();
  float min_x_m = -kUnbounded, max_x_m = kUnbounded;
  float min_y_m = -kUnbounded, max_y_m = kUnbounded;
  float min_z_m = -kUnbounded, max_z_m = kUnbounded;

  bool bounded() const;  // narrower than all of space on some axis
  bool contains(float x, float y, float z) const {
    return x >= min_x_m && x <= max_x_m && y >= min_y_m && y <= max_y_m && z >= min_z_m && z <= max_z_m;
  }
};

struct FilterConfig {
  std::uint32_t n_filter_supervoxels = 3;  // segments of <= this many supervoxels merge (A.4)
  // Beyond the paper: before A.4's rule (the largest neighbour), each small
  // segment joins the neighbour it meets across its most convex edge, by eq.
  // (1)'s measure (n1 - n2) . d_hat, when that neighbour is not small itself
  // (otherwise it waits, and follows once that neighbour has joined a larger
  // one). A small segment is a patch that noise cut off by edges eq. (5) calls
  // not convex; LCCP's premise is that concave edges part surfaces, and the
  // largest neighbour may lie across a deep concavity: a piece of a mug's
  // handle, 2 voxels thick at P1, meets the body at a measure of -0.6 to -1.3
  // and the rest of the handle at -0.02 to +0.01. Off by default and in P1 and
  // P2, where it moved the mOSD scores by less than their spread between the
  // test and the learn scenes; on in config/robot.yaml, whose objects are built
  // from the parts (perf/RESULTS.md, "Session of 2026-12-06 23:27").
  bool by_convexity = false;
  // Beyond the paper: the paper labels a point with its voxel's supervoxel,
  // and a voxel (v wide) that straddles a crease or a contact holds points of
  // both surfaces. With this key, a point of a voxel with a 26-neighbour in
  // another segment goes to that neighbour's segment when the plane of the
  // neighbour's supervoxel (centroid and normal) is kClearFit times nearer to
  // it than its own supervoxel's plane: it lies on the other surface, not
  // merely near the seam (a point about as near to both stays). With a support
  // plane, whose noise is then known, a point within one sample's centring
  // tolerance of its own plane (half a depth step plus three times the plane's
  // noise) stays too: it may lie on it (in four Kinect-noise views of the robot
  // battery, noisy points moved across a seam's end made a box 11.9 mm too long
  // or tilted its axis 2.4 deg). On by default and in P1, P2 (mOSD test and
  // learn scenes up, perf/RESULTS.md "Session of 2026-12-07 03:28") and
  // robot.yaml (two noise-free battery views within 5 mm, "Session of
  // 2026-12-07 10:29"); off in paper.yaml.
  bool boundary_points_by_plane = true;
  static constexpr float kClearFit = 4.0f;
  // Beyond the paper, at the object level only (SceneSegmenter, after stage 8):
  // an object of fewer points than this is no object: its points get label 0,
  // unassigned, as points outside the region do. Merging them is not an
  // option: with beta_thresh 180 deg every edge is convex, so an object is a
  // connected component of the supervoxel graph and a small one has no
  // neighbour to join (the noise filter, A.4, already merged those that had).
  // Default 0 (off, the paper). objects.yaml and robot.yaml: 25, the points a
  // VGA depth camera (f = 525 px) puts on a 2 cm square face at 2 m, the far
  // end of a table-top robot's reach: (525 * 0.02 / 2)^2 = 27.6. Anything
  // smaller there is less than the smallest thing a gripper picks up (a bottle
  // cap), and what it removes are flying pixels along depth edges and
  // scan-line fragments of far surfaces (5-20 points, a few mm wide). Farther
  // or with a coarser sensor a real object gives fewer points: lower it.
  std::uint32_t min_object_points = 0;
};

// Bounds on the work one cloud may ask for; a cloud or config beyond them is
// refused with one line naming the limit (never a crash, hang or silent
// collapse). Supervoxels and seeds are bounded by max_voxels.
struct LimitsConfig {
  std::uint32_t max_points = 50'000'000;  // points per cloud
  std::uint32_t max_voxels = 20'000'000;  // occupied voxels per cloud
  std::uint32_t max_growth_passes = 100;  // int(1.8 s / v) - 1; P1 needs 6, P2 13
  // |x|, |y|, |z| of every finite point. float spacing at 500 m is 61 um, an
  // 80th of the P1 voxel; validate() keeps it below v / 16 for any v.
  float max_coordinate_m = 500.0f;
};

// Beyond the paper, for a robot on a cluttered table (SceneSegmenter, stage 9,
// src/objects/grouping.cpp): with objects_from_parts, this level's segments
// are the parts, and the objects are unions of them, grouped by how they rest
// on the support plane. A part that touches the support (its lowest point
// within contact_m of the plane), or that meets another part, below its own
// top third, where that part's surface faces up (it rests on an upward face:
// a box on a box), is the body of an object of its own. A part that does neither hangs off the side
// of a neighbour (a handle, a spout, a knob) and joins the neighbour it shares
// most supervoxel edges with; so does a part lying inside a neighbour's
// footprint, below its top (a container's floor), a part standing on a
// flat part, not on the support, that meets a neighbour at a rim, both tops
// at one height (a pan's far inner wall on its raised floor), a part that continues
// another behind a nearer object (occluded_gap_m), a part hanging in the
// air beside a nearer body it vanishes behind, within a seed spacing of it
// (a handle whose ends the mug hides), and a part the sensor sees over a
// neighbour's rim (a bowl's inside). Parts with no body of their own that
// meet within one object are one part (a handle cut in two). The paper's object level
// (beta_thresh 180 deg after plane removal, config/paper-robot.yaml) joins
// every pair of touching objects. Needs the support plane. With it, the noise
// filter (A.4) first offers a small segment the neighbours it does not stand
// on: one whose centroid lies above a neighbour's upward face by more than the
// noise of a mean of its voxels is no noise on that face (a sliver of a box's
// side, seen edge on, standing on a lower box).
struct GroupingConfig {
  bool objects_from_parts = false;
  // A Kinect's noise at a table's range (3 sigma at 1.5 m: 1.2 cm, SensorConfig)
  // and the old support band (1 cm) both leave a standing object's foot this close.
  float contact_m = 0.015f;
  // A face tilted less than this from the support's normal faces up: a thing
  // can rest on it (the friction cone of most household surfaces is narrower).
  float upward_max_tilt_deg = 45.0f;
  // The cosine of upward_max_tilt_deg: a unit normal whose dot product with
  // the support's is at least this faces up.
  double cos_upward() const { return std::cos(upward_max_tilt_deg * std::numbers::pi / 180.0); }
  // Two parts that do not touch are one surface seen on either side of a
  // nearer object when the paper's convexity test (eq. (5)) joins their
  // nearest patches across the gap and the sensor cannot see the gap
  // (src/objects/occlusion.hpp); gaps up to this wide (a mug or a box in
  // front of a box). Also how far behind a nearer body a part hanging in the
  // air may vanish and be held by it. 0: neither.
  float occluded_gap_m = 0.15f;
};

struct LccpConfig {
  RegionConfig region;
  SupportPlaneConfig support;
  VoxelConfig voxels;
  NormalConfig normals;
  SupervoxelConfig supervoxels;
  SensorConfig sensor;
  ConvexityConfig convexity;
  FilterConfig filter;
  GroupingConfig grouping;
  LimitsConfig limits;
};

// A run's configuration: one level of LCCP, or two, as in the paper's robot
// application (Sec. III.C, Fig. 5 B and C): objects first (after the support
// plane is removed), then each object partitioned into parts.
//
// Or, with objects.grouping.objects_from_parts, the first level's segments are
// the parts and the objects are unions of them (GroupingConfig); `parts` is
// then empty. Either way a two-level result has objects and parts.
struct SceneConfig {
  LccpConfig objects;               // the first level: each of its segments is an object (or a part, grouping)
  std::optional<LccpConfig> parts;  // the second level, within each object; empty: one level (or grouping)

  bool two_levels() const { return parts.has_value() || objects.grouping.objects_from_parts; }
};

// VCCS's number of growth passes for seed size s and voxel size v: int(1.8 s / v) - 1,
// at least 1 (PCL's SupervoxelClustering::expandSupervoxels).
int growth_passes(float seed_size_m, float voxel_size_m);

// Throws lccp::Error naming the first out-of-range field.
void validate(const LccpConfig& config);
// Both levels; the part level works within objects, so it removes no support plane.
void validate(const SceneConfig& config);

}  // namespace lccp
