// World<Quad> (world_impl.hpp).
#include "world_impl.hpp"

namespace pge {
template class World<Quad>;
}  // namespace pge
