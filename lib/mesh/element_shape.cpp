#include "mesh/element_shape.hpp"

#include <array>
#include <string>

#include "core/error.hpp"

namespace fem {
namespace {
struct ShapeInfo { ElementShape shape; std::string_view name; int nodes; int dim; };
constexpr std::array<ShapeInfo, 9> kShapes = {{
    {ElementShape::Point1, "point1", 1, 0}, {ElementShape::Beam2, "beam2", 2, 1},
    {ElementShape::Tri3, "tri3", 3, 2},     {ElementShape::Quad4, "quad4", 4, 2},
    {ElementShape::Quad8, "quad8", 8, 2},   {ElementShape::Tet4, "tet4", 4, 3},
    {ElementShape::Tet10, "tet10", 10, 3},  {ElementShape::Hex8, "hex8", 8, 3},
    {ElementShape::Hex20, "hex20", 20, 3},
}};
const ShapeInfo& info(ElementShape s) {
    for (const auto& i : kShapes)
        if (i.shape == s) return i;
    throw std::logic_error("unknown element shape");
}
}  // namespace

std::string_view to_string(ElementShape shape) { return info(shape).name; }
int node_count(ElementShape shape) { return info(shape).nodes; }
int dimension(ElementShape shape) { return info(shape).dim; }

ElementShape element_shape_from_string(std::string_view name) {
    for (const auto& i : kShapes)
        if (i.name == name) return i.shape;
    throw InputError("unknown element shape '" + std::string(name) +
                     "' (known: point1, beam2, tri3, quad4, quad8, tet4, tet10, hex8, hex20)");
}

}  // namespace fem
