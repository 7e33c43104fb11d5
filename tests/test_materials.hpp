#pragma once
// The materials the unit tests share, each name with one meaning across every test folder: a unity
// build compiles several test files as one translation unit (CMakeLists.txt, fem_unity), where two
// files' `kSteel` with different constants would collide (and read ambiguously besides).
#include "material/elastic.hpp"

namespace fem::test {

inline const ElasticMaterial kSteel = ElasticMaterial::make("steel", 210e9, 0.3, 7800);
inline const ElasticMaterial kShellSteel = ElasticMaterial::make("steel", 210e9, 0.28, 7700);     // the shell plates
inline const ElasticMaterial kWireSteel = ElasticMaterial::make("steel wire", 209e9, 0.3, 7957);  // Table 2-8
inline const ElasticMaterial kRubber = ElasticMaterial::make("rubber", 5e6, 0.49, 1100);
inline const ElasticMaterial kFingerRubber = ElasticMaterial::make("rubber", 6.1e6, 0.45, 1000);
inline const ElasticMaterial kSoftRubber = ElasticMaterial::make("rubber", 2.0e6, 0.45, 1100.0);

}  // namespace fem::test
