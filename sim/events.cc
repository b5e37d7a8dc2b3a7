#include "sim/events.h"

namespace dimer::sim {

std::string ToString(EventKind k) {
  switch (k) {
    case EventKind::kImpact: return "impact";
    case EventKind::kDoubleImpact: return "double_impact";
    case EventKind::kCollapse: return "collapse";
    case EventKind::kLiftoff: return "liftoff";
    case EventKind::kStick: return "stick";
    case EventKind::kSlip: return "slip";
    case EventKind::kPainleve: return "painleve";
  }
  return "?";
}

}  // namespace dimer::sim
