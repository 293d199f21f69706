// A job's stages, as StageTimes records them and a Progress shows them: begin(name)
// ends the stage before it, timing it, and tells the progress (which may cancel the
// job there); end() times the last one. Internal to the job layer.
#pragma once

#include "meander/pipeline.h"
#include "meander/progress.h"

#include <chrono>
#include <string>

namespace meander {

class Stages {
public:
  Stages(StageTimes* times, Progress* progress) : times_(times), progress_(progress) {}

  void begin(const char* stage) {
    end();
    name_ = stage;
    if (progress_) progress_->begin(stage);
  }
  // The first stage's time counts from the construction.
  void end() {
    if (name_.empty()) return;
    const auto now = std::chrono::steady_clock::now();
    if (times_) times_->emplace_back(name_, std::chrono::duration<double>(now - start_).count());
    name_.clear();
    start_ = now;
  }

private:
  StageTimes* times_;
  Progress* progress_;
  std::string name_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

} // namespace meander
