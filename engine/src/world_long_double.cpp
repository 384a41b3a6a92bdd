// World<long double> (world_impl.hpp).
#include "world_events.hpp"
#include "world_api.hpp"
#include "world_predict.hpp"
#include "world_refine.hpp"
#include "world_broad_phase.hpp"
#include "world_rest.hpp"
#include "world_response.hpp"
#include "world_rotation.hpp"
#include "world_validate.hpp"

namespace pge {
template class World<long double>;
}  // namespace pge
