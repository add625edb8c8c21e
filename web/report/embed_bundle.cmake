# cmake -DIN=report_bundle.js -DOUT=report_bundle.cpp -P embed_bundle.cmake
# Writes a C++ source that defines biped::report_bundle() as the text of IN (a raw string literal).
file(READ "${IN}" bundle)
foreach(forbidden ")biped_bundle\"" "</script" "<!--")
  string(FIND "${bundle}" "${forbidden}" at)
  if(NOT at EQUAL -1)
    message(FATAL_ERROR "${IN} contains '${forbidden}': it cannot be inlined in report.html")
  endif()
endforeach()
file(WRITE "${OUT}.tmp" "// Generated from ${IN} by web/report/embed_bundle.cmake.
#include <string_view>

#include \"io/report.hpp\"

namespace biped {

std::string_view report_bundle() {
  static constexpr char kBundle[] = R\"biped_bundle(${bundle})biped_bundle\";
  return {kBundle, sizeof(kBundle) - 1};
}

}  // namespace biped
")
file(RENAME "${OUT}.tmp" "${OUT}")
