// Timings found through the pipeline: milliseconds per timing row (a frame's, or a run's median
// per row) read by pass type, so an experiment does not depend on the labels a pipeline's JSON
// gives its passes. Rows are the pipeline's labels ("label" and "label/part", Pipeline::execute).
#pragma once
#include <map>
#include <string>

#include "core/profiler.h"
#include "pipeline/pipeline.h"

namespace tandem {

class PassTimes {
 public:
  PassTimes(const Pipeline& pipeline, std::map<std::string, double> msByRow);
  // One frame's rows.
  PassTimes(const Pipeline& pipeline, const FrameTimings& frame);

  // The passes of `type`, summed; a type the pipeline lacks throws (a pass renamed or dropped
  // must not read as 0 ms).
  double ofType(const std::string& type) const;
  // Pass `index` of the pipeline (0 when it did not run).
  double ofPass(size_t index) const;
  // A part the passes of `type` report ("visibility"), summed; 0 where none reported it.
  double partOf(const std::string& type, const std::string& part) const;
  bool has(const std::string& type) const;
  // The rays the passes of `type` traced (one frame's rows only; 0 from medians).
  double raysOf(const std::string& type) const;
  // Every row renamed by type: "type" for a pass, "type/part" for its parts (instances of one
  // type summed); rows of no pass ("scene_update", "gpu_submit", "history") keep their names.
  std::map<std::string, double> byType() const;

 private:
  const Pipeline& pipeline_;
  std::map<std::string, double> ms_, rays_;
};

}  // namespace tandem
