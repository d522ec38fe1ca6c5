#include "lccp/io/config_file.hpp"

#include <array>
#include <charconv>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>
#include <string_view>
#include <system_error>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "lccp/error.hpp"

namespace lccp {
namespace {

namespace fs = std::filesystem;

// One configurable parameter: its key (unit in the name), what it means, and
// how to read and show it.
struct Key {
  std::string_view name;
  std::string_view meaning;
  std::function<void(LccpConfig&, const std::string&)> set;
  std::function<std::string(const LccpConfig&)> get;
};

// User text in a message, kept on one short line.
std::string printable(std::string_view text) {
  std::string out(text.substr(0, 60));
  for (char& c : out) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  }
  return text.size() > 60 ? out + "..." : out;
}

// A number, or an infinity as YAML writes it (.inf, -.inf) or as C++ does (inf, -inf).
float parse_float(std::string_view key, const std::string& text) {
  const bool signed_text = !text.empty() && (text[0] == '-' || text[0] == '+');
  const std::string_view magnitude = std::string_view(text).substr(signed_text ? 1 : 0);
  if (magnitude == ".inf" || magnitude == ".Inf" || magnitude == ".INF") {
    return text[0] == '-' ? -std::numeric_limits<float>::infinity() : std::numeric_limits<float>::infinity();
  }
  float value = 0.0f;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error == std::errc::result_out_of_range && end == text.data() + text.size()) {  // a number, not a float
    throw Error("config key '" + std::string(key) + "': '" + printable(text) +
                "' is out of range (a float: magnitude from 1.2e-38 to 3.4e38, or 0)");
  }
  if (error != std::errc{} || end != text.data() + text.size()) {
    throw Error("config key '" + std::string(key) + "': '" + printable(text) + "' is not a number");
  }
  return value;
}

std::uint32_t parse_count(std::string_view key, const std::string& text) {
  std::uint32_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error == std::errc::result_out_of_range && end == text.data() + text.size()) {
    throw Error("config key '" + std::string(key) + "': '" + printable(text) + "' is out of range (at most 4294967295)");
  }
  if (error != std::errc{} || end != text.data() + text.size()) {
    throw Error("config key '" + std::string(key) + "': '" + printable(text) + "' is not a whole number >= 0");
  }
  return value;
}

bool parse_bool(std::string_view key, const std::string& text) {
  if (text == "true" || text == "on" || text == "1") return true;
  if (text == "false" || text == "off" || text == "0") return false;
  throw Error("config key '" + std::string(key) + "': '" + printable(text) + "' is not true or false");
}

Binning parse_binning(std::string_view key, const std::string& text) {
  if (text == "auto") return Binning::automatic;
  if (text == "euclidean") return Binning::euclidean;
  if (text == "camera") return Binning::camera;
  if (text == "organized") return Binning::organized;
  throw Error("config key '" + std::string(key) + "': '" + printable(text) + "' is not auto, euclidean, camera or organized");
}

Growth parse_growth(std::string_view key, const std::string& text) {
  if (text == "flood") return Growth::flood;
  if (text == "vccs") return Growth::vccs;
  throw Error("config key '" + std::string(key) + "': '" + printable(text) + "' is not flood or vccs");
}

std::string show(float value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

std::string show(Binning binning) {
  switch (binning) {
    case Binning::euclidean: return "euclidean";
    case Binning::camera: return "camera";
    case Binning::organized: return "organized";
    case Binning::automatic: break;
  }
  return "auto";
}

// A float parameter; `field` is a generic lambda returning a reference to it.
template <typename Field>
Key float_key(std::string_view name, Field field, std::string_view meaning) {
  return {name, meaning, [=](LccpConfig& c, const std::string& t) { field(c) = parse_float(name, t); },
          [=](const LccpConfig& c) { return show(field(c)); }};
}

// A true/false parameter, like float_key.
template <typename Field>
Key bool_key(std::string_view name, Field field, std::string_view meaning) {
  return {name, meaning, [=](LccpConfig& c, const std::string& t) { field(c) = parse_bool(name, t); },
          [=](const LccpConfig& c) { return std::string(field(c) ? "true" : "false"); }};
}

// A whole-number parameter, like float_key.
template <typename Field>
Key count_key(std::string_view name, Field field, std::string_view meaning) {
  return {name, meaning, [=](LccpConfig& c, const std::string& t) { field(c) = parse_count(name, t); },
          [=](const LccpConfig& c) { return std::to_string(field(c)); }};
}

// What is segmented: the region of interest and the support plane.
std::vector<Key> scene_keys() {
  return {
      float_key("region_min_x_m", [](auto& c) -> auto& { return c.region.min_x_m; },
                "region of interest: points outside the box are not segmented (metres; -inf: unbounded)"),
      float_key("region_max_x_m", [](auto& c) -> auto& { return c.region.max_x_m; }, "region of interest, largest x (inf: unbounded)"),
      float_key("region_min_y_m", [](auto& c) -> auto& { return c.region.min_y_m; }, "region of interest, smallest y"),
      float_key("region_max_y_m", [](auto& c) -> auto& { return c.region.max_y_m; }, "region of interest, largest y"),
      float_key("region_min_z_m", [](auto& c) -> auto& { return c.region.min_z_m; }, "region of interest, smallest z (camera: nearest depth)"),
      float_key("region_max_z_m", [](auto& c) -> auto& { return c.region.max_z_m; }, "region of interest, largest z (camera: farthest depth)"),
      bool_key("support_plane", [](auto& c) -> auto& { return c.support.enabled; },
               "remove the support plane first, Sec. III.C (true/false)"),
      float_key("support_distance_m", [](auto& c) -> auto& { return c.support.distance_m; },
                "points this close to the plane are on it (metres)"),
      float_key("support_up_x", [](auto& c) -> auto& { return c.support.up_x; }, "expected up direction, x (0 0 0: any)"),
      float_key("support_up_y", [](auto& c) -> auto& { return c.support.up_y; }, "expected up direction, y"),
      float_key("support_up_z", [](auto& c) -> auto& { return c.support.up_z; }, "expected up direction, z"),
      float_key("support_max_tilt_deg", [](auto& c) -> auto& { return c.support.max_tilt_deg; },
                "largest angle between plane normal and up (degrees)"),
      float_key("support_min_share", [](auto& c) -> auto& { return c.support.min_inlier_share; },
                "fewer inliers (share of finite points): no plane"),
      count_key("support_iterations", [](auto& c) -> auto& { return c.support.iterations; }, "RANSAC hypotheses"),
      float_key("support_noise_sigmas", [](auto& c) -> auto& { return c.support.noise_sigmas; },
                "on the plane within this many of its inliers' robust sigmas, scaled as z^2 (0: support_distance_m)"),
      bool_key("support_by_patches", [](auto& c) -> auto& { return c.support.decided_by_patches; },
               "band points near other points are segmented with them; the patches decide (true/false)"),
      bool_key("objects_from_parts", [](auto& c) -> auto& { return c.grouping.objects_from_parts; },
               "segments are parts; objects are their unions by support (true/false)"),
      float_key("object_contact_m", [](auto& c) -> auto& { return c.grouping.contact_m; },
                "a part whose lowest point is this close to the support stands on it (metres)"),
      float_key("upward_max_tilt_deg", [](auto& c) -> auto& { return c.grouping.upward_max_tilt_deg; },
                "a face this close to the support's normal faces up (degrees)"),
      float_key("occluded_gap_m", [](auto& c) -> auto& { return c.grouping.occluded_gap_m; },
                "parts this far apart may be one surface behind a nearer object, a part hanging in the air "
                "this far behind a body be held by it (metres; 0: never)"),
  };
}

// The method, stage by stage: voxels, normals, supervoxels, convexity, the noise filter.
std::vector<Key> method_keys() {
  return {
      float_key("voxel_size_m", [](auto& c) -> auto& { return c.voxels.voxel_size_m; }, "voxel size v (metres)"),
      Key{"binning", "voxel cells: auto (camera if every point is in a camera's view from the origin), euclidean, camera or organized (PCL's: camera if organized)",
          [](LccpConfig& c, const std::string& t) { c.voxels.binning = parse_binning("binning", t); },
          [](const LccpConfig& c) { return show(c.voxels.binning); }},
      bool_key("crease_preserving_normals", [](auto& c) -> auto& { return c.normals.crease_preserving; },
               "beyond the paper: normals near a crease from the flattest neighbourhood they lie on (true/false)"),
      float_key("planar_variation", [](auto& c) -> auto& { return c.normals.planar_variation; },
                "flood: a voxel normal is a plane's at most at this surface variation (least eigenvalue / trace)"),
      Key{"growth", "supervoxel growth: flood (beyond the paper: each voxel once, never across a crease or step) or vccs",
          [](LccpConfig& c, const std::string& t) { c.supervoxels.growth = parse_growth("growth", t); },
          [](const LccpConfig& c) { return std::string(c.supervoxels.growth == Growth::flood ? "flood" : "vccs"); }},
      float_key("seed_size_m", [](auto& c) -> auto& { return c.supervoxels.seed_size_m; }, "supervoxel seed spacing s (metres)"),
      bool_key("depth_scaled_seeds", [](auto& c) -> auto& { return c.supervoxels.depth_scaled_seeds; },
               "beyond the paper: camera cells beyond s / (4 v) metres get seeds 4 cells apart (true/false)"),
      float_key("max_normal_angle_deg", [](auto& c) -> auto& { return c.supervoxels.max_normal_angle_deg; },
                "flood: a patch admits voxels whose normal is within this angle of its own (degrees)"),
      float_key("spatial_weight", [](auto& c) -> auto& { return c.supervoxels.spatial_weight; }, "w_s, per seed spacing of distance"),
      float_key("normal_weight", [](auto& c) -> auto& { return c.supervoxels.normal_weight; }, "w_n, on 1 - |n1.n2|"),
      float_key("color_weight", [](auto& c) -> auto& { return c.supervoxels.color_weight; }, "w_c, on |rgb1 - rgb2| / 255"),
      float_key("beta_thresh_deg", [](auto& c) -> auto& { return c.convexity.beta_thresh_deg; }, "CC bias beta_thresh (degrees), eq. 1"),
      bool_key("sanity_criterion", [](auto& c) -> auto& { return c.convexity.sanity_criterion; }, "apply SC, eq. 4 (true/false)"),
      float_key("theta_max_deg", [](auto& c) -> auto& { return c.convexity.theta_max_deg; }, "SC sigmoid maximum (degrees), eq. 3"),
      bool_key("smoothness_check", [](auto& c) -> auto& { return c.convexity.smoothness_check; },
               "PCL's step test beyond the paper: cut edges between offset patches (true/false)"),
      bool_key("corner_check", [](auto& c) -> auto& { return c.convexity.corner_check; },
               "beyond the paper: a convex edge at least 90 deg sharp needs each patch behind the other's plane (true/false)"),
      float_key("smoothness_threshold", [](auto& c) -> auto& { return c.convexity.smoothness_threshold; },
                "smoothness check's slack, in voxel sizes v (PCL's default 0.1)"),
      float_key("beta_off_deg", [](auto& c) -> auto& { return c.convexity.beta_off_deg; }, "SC sigmoid offset (degrees), eq. 3"),
      float_key("sigmoid_slope_per_deg", [](auto& c) -> auto& { return c.convexity.sigmoid_slope_per_deg; }, "SC sigmoid slope a (1/degree), eq. 3"),
      count_key("n_filter_supervoxels", [](auto& c) -> auto& { return c.filter.n_filter_supervoxels; },
                "segments of <= this many supervoxels merge into a neighbour (A.4)"),
      bool_key("filter_by_convexity", [](auto& c) -> auto& { return c.filter.by_convexity; },
               "beyond the paper: A.4 first joins a small segment to its neighbour across its most convex edge (true/false)"),
      bool_key("boundary_points_by_plane", [](auto& c) -> auto& { return c.filter.boundary_points_by_plane; },
               "beyond the paper: a point by a seam goes to the neighbouring segment whose patch plane clearly fits it (true/false)"),
      count_key("min_object_points", [](auto& c) -> auto& { return c.filter.min_object_points; },
                "objects of fewer points are dropped: their points get label 0 (0: keep all)"),
  };
}

// The depth sensor's noise model (SensorConfig).
std::vector<Key> sensor_keys() {
  return {
      bool_key("sensor_depth_steps", [](auto& c) -> auto& { return c.sensor.depth_steps; },
               "beyond the paper: camera cells and the smoothness check's slack at least one depth step deep (true/false)"),
      float_key("sensor_focal_px", [](auto& c) -> auto& { return c.sensor.focal_px; },
                "flood: the depth sensor's disparity focal length f (pixels)"),
      float_key("sensor_baseline_m", [](auto& c) -> auto& { return c.sensor.baseline_m; },
                "flood: the depth sensor's baseline b (metres)"),
      float_key("sensor_disparity_step_px", [](auto& c) -> auto& { return c.sensor.disparity_step_px; },
                "flood: the disparity's quantization d (pixels); depth steps are z^2 d / (f b)"),
      float_key("sensor_axial_sigma_m", [](auto& c) -> auto& { return c.sensor.axial_sigma_m; },
                "flood: the axial noise's standard deviation at the nearest range (metres)"),
      float_key("sensor_axial_sigma_per_m2", [](auto& c) -> auto& { return c.sensor.axial_sigma_per_m2; },
                "flood: its growth with the square of the depth beyond the nearest range (1/metre)"),
      float_key("sensor_min_range_m", [](auto& c) -> auto& { return c.sensor.min_range_m; },
                "flood: the sensor's nearest range (metres)"),
  };
}

// Bounds on the work one cloud may ask for (LimitsConfig).
std::vector<Key> limit_keys() {
  return {
      count_key("max_points", [](auto& c) -> auto& { return c.limits.max_points; }, "refuse clouds with more points"),
      count_key("max_voxels", [](auto& c) -> auto& { return c.limits.max_voxels; }, "refuse clouds filling more voxels"),
      count_key("max_growth_passes", [](auto& c) -> auto& { return c.limits.max_growth_passes; },
                "refuse seed/voxel sizes needing more growth passes"),
      float_key("max_coordinate_m", [](auto& c) -> auto& { return c.limits.max_coordinate_m; },
                "refuse clouds with a finite point farther along an axis (metres)"),
  };
}

const std::vector<Key>& keys() {
  static const std::vector<Key> table = [] {
    std::vector<Key> all;
    for (std::vector<Key> group : {scene_keys(), method_keys(), sensor_keys(), limit_keys()}) {
      all.insert(all.end(), group.begin(), group.end());
    }
    return all;
  }();
  return table;
}

std::string known_keys() {
  std::string names;
  for (const Key& key : keys()) names += (names.empty() ? "" : ", ") + std::string(key.name);
  return names;
}

void set_key(LccpConfig& config, const std::string& name, const std::string& value) {
  for (const Key& key : keys()) {
    if (key.name == name) return key.set(config, value);
  }
  throw Error("unknown config key '" + printable(name) + "' (known: " + known_keys() + ")");
}

constexpr std::size_t kMaxConfigBytes = 1 << 20;  // presets are a few hundred bytes

std::string at_line(const YAML::Mark& mark) {
  return mark.line >= 0 ? " (line " + std::to_string(mark.line + 1) + ")" : "";
}

constexpr std::string_view kPartsKey = "parts";  // the second level's map (SceneConfig::parts)

// One `key: value` entry: both must be plain scalars.
void apply_entry(LccpConfig& config, const YAML::Node& key, const YAML::Node& value, const std::string& file,
                 const std::string& prefix) {
  if (!key.IsScalar())
    throw Error(file + ": a config key must be a plain name, not a list or map" + at_line(key.Mark()));
  const std::string name = key.Scalar();
  if (!value.IsScalar()) throw Error(file + ": config key '" + prefix + printable(name) + "' needs a single value");
  try {
    set_key(config, name, value.Scalar());
  } catch (const Error& e) {
    throw Error(file + ": " + prefix + e.what());
  }
}

// The part level: a map of the same keys, starting from the defaults (P1).
LccpConfig parts_from_yaml(const YAML::Node& map, const std::string& file) {
  if (!map.IsMap()) throw Error(file + ": '" + std::string(kPartsKey) + "' needs a map of key: value" + at_line(map.Mark()));
  LccpConfig parts;
  for (const auto& entry : map) apply_entry(parts, entry.first, entry.second, file, "parts.");
  return parts;
}

SceneConfig config_from_yaml(const YAML::Node& root, const std::string& file) {
  SceneConfig config;
  if (root.IsNull()) return config;
  if (!root.IsMap()) throw Error(file + ": expected a map of key: value");
  for (const auto& entry : root) {
    if (entry.first.IsScalar() && entry.first.Scalar() == kPartsKey) {
      config.parts = parts_from_yaml(entry.second, file);
    } else {
      apply_entry(config.objects, entry.first, entry.second, file, "");
    }
  }
  try {
    validate(config);
  } catch (const Error& e) {
    throw Error(file + ": " + e.what());
  }
  return config;
}

}  // namespace

SceneConfig parse_config(std::string_view yaml_text, std::string_view name) {
  const std::string file(name);
  try {
    return config_from_yaml(YAML::Load(std::string(yaml_text)), file);
  } catch (const Error&) {
    throw;
  } catch (const YAML::Exception& e) {  // the parser's, or a node conversion's
    throw Error(file + ": not valid YAML" + at_line(e.mark) + " (" + printable(e.msg) + ")");
  }
}

SceneConfig load_config(const std::filesystem::path& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw Error(path.string() + ": cannot open config file (a directory)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path.string() + ": cannot open config file");
  std::string text(kMaxConfigBytes + 1, '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  if (in.bad()) throw Error(path.string() + ": cannot read config file");
  text.resize(static_cast<std::size_t>(in.gcount()));
  if (text.size() > kMaxConfigBytes)
    throw Error(path.string() + ": config file larger than " + std::to_string(kMaxConfigBytes) + " bytes");
  return parse_config(text, path.string());
}

void apply_setting(SceneConfig& config, const std::string& key_equals_value) {
  const auto equals = key_equals_value.find('=');
  if (equals == std::string::npos || equals == 0) {
    throw Error("--set expects key=value, got '" + printable(key_equals_value) + "'");
  }
  const std::string key = key_equals_value.substr(0, equals), value = key_equals_value.substr(equals + 1);
  const std::string parts_prefix = std::string(kPartsKey) + ".";
  if (!key.starts_with(parts_prefix)) return set_key(config.objects, key, value);
  if (!config.parts) throw Error("config key '" + printable(key) + "': this config has one level (no parts:)");
  try {
    set_key(*config.parts, key.substr(parts_prefix.size()), value);
  } catch (const Error& e) {
    throw Error(parts_prefix + e.what());
  }
}

std::string describe_config(const SceneConfig& config) {
  std::string text;
  for (const Key& key : keys()) {
    text += std::string(key.name) + ": " + key.get(config.objects) + "    # " + std::string(key.meaning) + "\n";
  }
  if (!config.parts) return text;
  for (const Key& key : keys()) {
    text += "parts." + std::string(key.name) + ": " + key.get(*config.parts) + "    # " + std::string(key.meaning) + "\n";
  }
  return text;
}

std::vector<std::string> config_key_names(const SceneConfig& config) {
  std::vector<std::string> names;
  for (const Key& key : keys()) names.emplace_back(key.name);
  if (!config.parts) return names;
  for (const Key& key : keys()) names.push_back("parts." + std::string(key.name));
  return names;
}

}  // namespace lccp
