// eventNumber: a number as the instruments' and the wound's event lines print it (4 significant
// digits: "t = 0.411 s: the needle went into lip 0 ... 4.91 mm from its cut face").
#pragma once

#include <sstream>
#include <string>

namespace filum::haptics {

inline std::string eventNumber(double x) {
  std::ostringstream out;
  out.precision(4);
  out << x;
  return out.str();
}

}  // namespace filum::haptics
