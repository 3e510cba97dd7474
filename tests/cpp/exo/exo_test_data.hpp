#pragma once
// Where the exo tests find data/gait/winter_g3.csv: three folders above this file.

#include <string>

namespace pamkit_test {
inline std::string winter_csv() {
  const std::string here = __FILE__;
  std::string root = here;
  for (int i = 0; i < 4; ++i) root = root.substr(0, root.find_last_of('/'));
  return root + "/data/gait/winter_g3.csv";
}
}  // namespace pamkit_test
