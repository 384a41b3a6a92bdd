// World<float> (world_impl.hpp).
#include "world_impl.hpp"

namespace pge {
template class World<float>;
}  // namespace pge
