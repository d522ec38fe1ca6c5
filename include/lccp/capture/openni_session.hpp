#pragma once
// OpenNI2, initialized once per process.
#include <string>

namespace lccp {

// Initializes OpenNI2 on first use; later calls return at once. OpenNI2 changes
// the working directory and may log to stdout while it loads its drivers: both
// are undone here, so relative output paths and stdout stay ours. Drivers come
// from OpenNI2/Drivers beside the libOpenNI2.so.0 the executable loaded
// (OpenNI2 Source/Core/OniContext.cpp, unless OpenNI.ini names another folder).
// Throws lccp::Error with OpenNI2's message if initialization fails.
void initialize_openni();

// OpenNI2's last error message on one line (tabs and newlines folded).
std::string openni_error();

}  // namespace lccp
