// World<double> (world_impl.hpp).
#include "world_impl.hpp"

namespace pge {
template class World<double>;
}  // namespace pge
