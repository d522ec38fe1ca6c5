#pragma once
// The public API of LCCP Stream in one include (find_package(LccpStream) gives
// the target LccpStream::lccp). Lengths are metres in the input cloud's frame,
// angles as each config key names them, times milliseconds.
//
// Segment a cloud:
//   lccp::PointCloud cloud = lccp::read_cloud("scene.pcd").cloud;         // io/cloud_io.hpp
//   lccp::SceneSegmenter segmenter(lccp::load_preset_or_file("p1"));      // io/config_file.hpp
//   lccp::SceneSegmentation scene = segmenter.segment(cloud);             // objects/scene.hpp
//   scene.labels[i]        the segment id of point i (0: no data)
//   scene.segments[k]      the k-th object's geometry (objects/geometry.hpp) and its parts
//   your own memory:       segmenter.segment(lccp::CloudView{...})        // cloud.hpp, read in place
//
// Run a stream (a recording, a device URI or cloud files), a callback per frame:
//   auto source = lccp::open_source({"recordings/mosd_scenes.oni"});     // capture/open_source.hpp
//   lccp::Pipeline(segmenter, {.frames_in_flight = 2})                     // pipeline/pipeline.hpp
//       .run(*source, [](lccp::FrameResult& r) { ... r.segmentation ... });
// or in the background, frames taken when you want them (pipeline/background_stream.hpp):
//   lccp::BackgroundStream stream(config, *source, {.frames_in_flight = 2});
//   lccp::FrameResult r;  while (stream.next(r, 100ms) != lccp::BackgroundStream::Next::ended) ...
// Frames that come from elsewhere (your own driver, messages): a lccp::PushSource
// (pipeline/push_source.hpp) as the source, push(frame) from any thread.
//
// Write and score results: write_labelled_cloud, write_label_png (io/cloud_io.hpp),
// write_segments_json (io/segments_json.hpp), score_segmentation (metrics/scores.hpp).
//
// Thread safety: a SceneSegmenter is immutable after construction; segment() may
// run on several threads at once (each call has its own work). Pipeline::run
// blocks until the stream ends and calls the sink from one thread at a time; it
// reads the source on a thread of its own and segments on oneTBB's threads:
// limit those with a tbb::task_arena around the call (a BackgroundStream has
// an arena of its own: StreamConfig::threads).
#include "lccp/capture/open_source.hpp"
#include "lccp/cloud.hpp"
#include "lccp/config.hpp"
#include "lccp/error.hpp"
#include "lccp/io/cloud_io.hpp"
#include "lccp/io/config_file.hpp"
#include "lccp/io/segments_json.hpp"
#include "lccp/metrics/scores.hpp"
#include "lccp/objects/scene.hpp"
#include "lccp/pipeline/background_stream.hpp"
#include "lccp/pipeline/pipeline.hpp"
#include "lccp/pipeline/push_source.hpp"
