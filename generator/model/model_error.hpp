// The one error type of model loading: it names the file, the place in it
// and what to do, so every bad input ends in one clear line.
#pragma once

#include <stdexcept>
#include <string>

namespace kanegen::model {

class ModelError : public std::runtime_error {
 public:
  /// file: the model file; place: a JSON pointer ("/joints/2/axis"), an URDF
  /// element ("<joint name=\"j1\">/axis") or an expression with a caret;
  /// problem: what is wrong; fix: how to fix it.
  ModelError(std::string file, std::string place, std::string problem, std::string fix)
      : std::runtime_error(file + ": " + (place.empty() ? std::string("/") : place) + ": " + problem +
                           (fix.empty() ? std::string() : "; " + fix)),
        file_(std::move(file)),
        place_(std::move(place)) {}

  const std::string& file() const { return file_; }
  const std::string& place() const { return place_; }

 private:
  std::string file_;
  std::string place_;
};

}  // namespace kanegen::model
