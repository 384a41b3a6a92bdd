// World<long double> (world_impl.hpp).
#include "world_impl.hpp"

namespace pge {
template class World<long double>;
}  // namespace pge
