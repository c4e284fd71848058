#pragma once
// A user's YAML, XML or JSON file opened through OpenCV's FileStorage (camera files, marker dictionaries). Every
// failure is one Error naming the file and its role: OpenCV's parser throws cv::Exception and, on some malformed
// files, std::length_error from inside its own code; on others it never returns, so a trial parse in a child process
// is bounded in time.
#include <string>

#include <opencv2/core/persistence.hpp>

namespace surfscatter::photo {

// Opens `path` into `fs` for reading; `what` names the file's role ("camera file").
void open_for_reading(cv::FileStorage& fs, const std::string& path, const char* what);

}  // namespace surfscatter::photo
