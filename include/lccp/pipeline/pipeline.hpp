#pragma once
// The streaming pipeline: a oneTBB flow graph that segments a stream of frames
// with several frames in flight and hands results over in frame order.
//
//   source (read on a capture thread) -> admission (K slots) -> back-projection
//          -> one node per kPipelineNodes entry but the last (the stages of
//             kStages), frames in parallel -> sequencer -> the last node (stable
//             ids, the stream's tracker) in frame order -> sink
//          -> the slot goes back to admission
#include <array>
#include <cstdint>
#include <functional>
#include <mutex>
#include <stop_token>
#include <string>
#include <string_view>

#include "lccp/frame_source.hpp"
#include "lccp/frame.hpp"
#include "lccp/objects/scene.hpp"
#include "lccp/stages.hpp"

namespace lccp {

// The pipeline's flow-graph nodes, each a run of consecutive stages of kStages
// (first to last). Every node but the last runs frames in parallel; the last
// runs them one at a time in frame order.
struct PipelineNode {
  std::string_view name;
  Stage first;
  Stage last;

  bool contains(Stage stage) const { return first <= stage && stage <= last; }
  double ms(const StageTimes& times) const {  // the node's share of a frame's times
    double sum = 0;
    for (const StageInfo& info : kStages) sum += contains(info.stage) ? times[info.stage] : 0.0;
    return sum;
  }
};

inline constexpr std::array<PipelineNode, 5> kPipelineNodes{{
    {"voxelize_normals", Stage::support, Stage::normals},
    {"supervoxels", Stage::seeds, Stage::growth},
    {"graph_labels", Stage::adjacency, Stage::filter},
    {"parts_geometry", Stage::parts, Stage::geometry},
    {"ids", Stage::ids, Stage::ids},
}};

// What happens to a frame that arrives while K frames are already in flight.
enum class DropPolicy {
  block,        // wait: lossless (recordings, files)
  drop_oldest,  // a live source keeps running: the oldest waiting frame is dropped, the newest gets through
};

// Live sources (a sensor, --realtime replay) drop the oldest; others block.
inline DropPolicy drop_policy_for(const FrameSource& source) {
  return source.is_live() ? DropPolicy::drop_oldest : DropPolicy::block;
}

struct FrameResult;
struct PipelineStats;

// Watches a run (the live view, lccp/view/view_server.hpp): sees every frame
// handed over, just before the sink does (in frame order, one call at a time,
// on the sink's thread), with the counts as they stand; then the run's final
// counts. It must return quickly: the run waits for it. An exception from
// publish() counts as the sink's.
class RunObserver {
 public:
  virtual ~RunObserver() = default;
  virtual void publish(const FrameResult& result, const PipelineStats& stats) = 0;
  virtual void finish(const PipelineStats& stats) = 0;
};

struct PipelineConfig {
  unsigned frames_in_flight = 2;     // K >= 1: frames in the graph at once
  RunObserver* observer = nullptr;   // outlives the runs; none: nothing is watched
  bool warm_up = true;               // live sources: K synthetic frames first, thrown away (pipeline.cpp)
};

struct FrameResult {
  Frame frame;                      // its cloud is filled (back-projected if it came as depth)
  SceneSegmentation segmentation;   // ids per point of frame.cloud, per-segment geometry
  double back_projection_ms = 0;
  Clock::time_point labels_ready{};  // when the last stage finished
  // Empty if every stage succeeded. Otherwise the failing stage's message (e.g.
  // "no finite points"): the frame still reaches the sink, in order, with
  // every label 0 (one per point of frame.cloud) and the stage times measured
  // up to the failure; the stream goes on.
  std::string error;
  double end_to_end_ms() const {     // frame captured -> labels ready
    return std::chrono::duration<double, std::milli>(labels_ready - frame.captured).count();
  }
};

// What a run did with the frames. Every frame the source produced is counted
// once on each side:
//   frames_received + sensor_gaps == frames_completed + frames_failed + frames_dropped
struct PipelineStats {
  std::uint64_t frames_received = 0;   // taken from the source; one it hands over once a stop has
                                       // closed admission is not taken (a replay stopped drops none)
  std::uint64_t sensor_gaps = 0;       // frames the source skipped: index a then b adds b - a - 1
  std::uint64_t frames_completed = 0;  // handed to the sink with labels
  std::uint64_t frames_failed = 0;     // handed to the sink with a stage error, or the sink threw on them
  std::uint64_t frames_dropped = 0;    // never handed to the sink: the sensor gaps, frames dropped by
                                       // drop_oldest or left waiting (for a slot) at a stop, frames after the sink threw
  double wall_seconds = 0;

  bool adds_up() const {
    return frames_received + sensor_gaps == frames_completed + frames_failed + frames_dropped;
  }
};

// A run's PipelineStats as they stand, read from any thread while it runs
// (diagnostics). Frames in flight are in none of the counts on the right yet,
// and a gap counts as dropped when the frame after it is taken; the counts add
// up once the run has ended.
class LiveStats {
 public:
  PipelineStats snapshot() const {
    const std::lock_guard lock(mutex_);
    return stats_;
  }
  template <typename Update>
  void update(Update&& update) {
    const std::lock_guard lock(mutex_);
    update(stats_);
  }

 private:
  mutable std::mutex mutex_;
  PipelineStats stats_;
};

// How a run ended: its counts, and the error that ended it (the source's, e.g.
// "device ... disconnected", or the sink's), empty if the source ended or a
// stop was requested.
struct PipelineOutcome {
  PipelineStats stats;
  std::string error;
};

class Pipeline {
 public:
  // Throws lccp::Error for frames_in_flight == 0.
  Pipeline(const SceneSegmenter& segmenter, PipelineConfig config);

  // Pulls frames until the source ends, fails, or `stop` is requested; calls
  // `sink` for every frame that entered the graph, in frame order, one call at
  // a time, on a TBB thread. A stage error stays with its frame
  // (FrameResult::error). After a stop or a source error no frame is taken,
  // and the frames in flight are finished and handed to the sink. After a
  // sink error the frames in flight are finished but not handed over.
  // `live`, if given, is kept current as frames are taken and handed over.
  PipelineOutcome run(FrameSource& source, const std::function<void(FrameResult&)>& sink,
                      std::stop_token stop = {}, LiveStats* live = nullptr) const;

 private:
  const SceneSegmenter& segmenter_;
  PipelineConfig config_;
};

}  // namespace lccp
