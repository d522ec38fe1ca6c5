#pragma once
// One JSON document (RFC 8259) per frame describing its objects and parts for
// a robot (paper Sec. III.C): the support plane, each object's and part's
// geometry (lccp/objects/geometry.hpp) and the ids that came and went.
#include <cstdint>
#include <filesystem>
#include <string>

#include "lccp/objects/scene.hpp"

namespace lccp {

// The document, compact (no whitespace) with a newline at the end,
// deterministic (the same scene gives the same bytes). Lengths in metres in
// the input cloud's frame:
//
//   {"frame":N,"timestamp_us":T,
//    "support_plane":{"id":support_id,"normal":[x,y,z],"d":d} or null,
//    "objects":[{"id":I,"points":P,"centroid":[x,y,z],
//                "obb":{"center":[3],"axes":[[3],[3],[3]],"extents":[3]},
//                "principal_axes":[[3],[3],[3]],"principal_extents":[3],
//                "mean_normal":[3],"grasp":"top"|"side",
//                "adjacent":[{"id":J,"boundary":"convex"|"concave"}],
//                "parts":[the same fields but "parts", one per part; [] with one level]}],
//    "new_ids":[...],"gone_ids":[...]}
//
// The plane is normal . p + d = 0. Axes are listed as rows, each row one axis
// (a column of the Eigen matrix), in the matrix's column order. Numbers are
// the shortest decimal that reads back as the same float (at most 9
// significant digits, lossless; a whole number without a fraction), null
// where a value is NaN or infinite (JSON has neither).
std::string encode_segments_json(std::uint64_t frame_index, std::uint64_t timestamp_us,
                                 const SceneSegmentation& scene);

// The document written with write_file_atomically (lccp/io/atomic_file.hpp).
// Throws lccp::Error naming the path.
void write_segments_json(const std::filesystem::path& path, std::uint64_t frame_index, std::uint64_t timestamp_us,
                         const SceneSegmentation& scene);

}  // namespace lccp
