#include "sim/membrane/output/tear_path.hpp"

#include <fmt/format.h>

namespace ligsim::membrane {

std::string tear_path_csv(const TearMetrics& metrics)
{
  std::string text =
      "step,tip,initiation,criterion,from_x_mm,from_y_mm,to_x_mm,to_y_mm,split_face,load_n\n";
  for (const RecordedEvent& recorded : metrics.events) {
    const TearEvent& e = recorded.event;
    text +=
        fmt::format("{},{},{},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{},{:.6g}\n", recorded.step,
                    e.tip_id, e.initiation ? 1 : 0, e.criterion, e.from_rest.x(), e.from_rest.y(),
                    e.to_rest.x(), e.to_rest.y(), e.split_face ? 1 : 0, recorded.load_n);
  }
  return text;
}

} // namespace ligsim::membrane
