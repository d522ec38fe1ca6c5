// lccp_stream.evaluate(): the paper's Appendix B scores (score_segmentation,
// score_objects), as `lccp eval` computes them.
#include "bindings.hpp"
#include "lccp/metrics/scores.hpp"

namespace lccp::python {
namespace {

std::uint32_t label_bound(py::handle value) {
  const long long label = value.cast<long long>();
  if (label < 0 || label > std::uint32_t(-1)) {
    throw py::value_error("ignore: labels are from 0 to 4294967295, got " + std::to_string(label));
  }
  return static_cast<std::uint32_t>(label);
}

// ignore=range(a, b) (step 1, not empty), (first, last) inclusive, or None.
std::optional<LabelRange> ignored_range(py::handle ignore) {
  if (ignore.is_none()) return std::nullopt;
  if (py::isinstance(ignore, py::module_::import("builtins").attr("range"))) {
    if (ignore.attr("step").cast<long long>() != 1 || py::len(ignore) == 0) {
      throw py::value_error("ignore: expected a contiguous, non-empty range (step 1), got " +
                            py::repr(ignore).cast<std::string>());
    }
    return LabelRange{label_bound(ignore.attr("start")), label_bound(ignore.attr("stop").cast<py::int_>() - py::int_(1))};
  }
  if (py::isinstance<py::tuple>(ignore) && py::len(ignore) == 2) {
    const LabelRange range{label_bound(ignore[py::int_(0)]), label_bound(ignore[py::int_(1)])};
    if (range.first > range.last) throw py::value_error("ignore: the range (first, last) is empty");
    return range;
  }
  throw py::value_error("ignore: expected a range, a (first, last) tuple or None, got " +
                        py::repr(ignore).cast<std::string>());
}

// The points whose labels count: finite ones; with none given, all of them.
std::vector<Eigen::Vector3f> scored_points(py::handle points, std::size_t n) {
  if (points.is_none()) return std::vector<Eigen::Vector3f>(n, Eigen::Vector3f::Zero());
  const CloudView view = cloud_arrays(points).view();
  return {view.points.begin(), view.points.end()};
}

py::dict scores_dict(const SegmentationScores& s) {
  py::dict d;
  d["weighted_overlap"] = s.weighted_overlap;
  d["true_positive"] = s.true_positive;
  d["false_positive"] = s.false_positive;
  d["false_negative"] = s.false_negative;
  d["over_segmentation"] = s.over_segmentation;
  d["under_segmentation"] = s.under_segmentation;
  d["adjusted_rand_index"] = s.adjusted_rand_index;
  d["ground_truth_regions"] = s.ground_truth_regions;
  d["scored_points"] = s.scored_points;
  d["objects_lost"] = s.objects_lost;
  d["lost_labels"] = py::cast(s.lost_labels);
  return d;
}

py::dict evaluate(ArrayArg predicted, ArrayArg ground_truth, IgnoreArg ignore, OptionalArrayArg points,
                  bool object_level) {
  const Labels pred = labels_from(predicted, "pred");
  const Labels truth = labels_from(ground_truth, "gt");
  const std::optional<LabelRange> ignored = ignored_range(ignore);
  const std::vector<Eigen::Vector3f> xyz = scored_points(points, truth.size());
  SegmentationScores scores;
  {
    py::gil_scoped_release release;
    const auto score = object_level ? score_objects : score_segmentation;
    scores = score(pred, truth, xyz, ignored, kSupportLabels);
  }
  return scores_dict(scores);
}

}  // namespace

void bind_evaluate(py::module_& module) {
  module.def("evaluate", &evaluate, py::arg("pred"), py::arg("gt"),
             py::arg("ignore") = py::module_::import("builtins").attr("range")(10), py::arg("points") = py::none(),
             py::arg("object_level") = false, R"doc(
Scores predicted labels against ground-truth labels (the paper's Appendix B,
as lccp eval): weighted overlap, true/false positive and false negative
rates, over- and under-segmentation, the adjusted Rand index, and the
ground-truth regions lost into the support (labels 1-9).

pred, gt: integer labels, one per point, any shape (e.g. (H, W)).
ignore: ground-truth labels left out, a contiguous range (default range(10):
    mOSD's "no data" and table labels), an inclusive (first, last) tuple, or None.
points: the cloud (N, 3) or (H, W, 3); only its finite points are scored.
    None: every point is scored.
object_level: merge each object's parts n*10+k into one region n*10 first.

Returns a dict with the keys weighted_overlap, true_positive,
false_positive, false_negative, over_segmentation, under_segmentation,
adjusted_rand_index, ground_truth_regions, scored_points, objects_lost and
lost_labels (a list). Raises ValueError if the sizes differ or no
ground-truth region is left.
)doc");
}

}  // namespace lccp::python
