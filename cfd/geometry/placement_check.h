// Consistency of a hull's placement with its ship file: a surface read in the
// wrong unit, with the wrong waterline or AP, or turned end for end gives the
// same area and (nearly) the same volume, and the grid and forces are then
// quietly those of another ship. Each check compares what the surface says
// with what the ship file says and names the key to look at.
#pragma once

#include <string>
#include <vector>

#include "cfd/geometry/hydrostatics.h"

namespace kelvin::cfd {

// Warnings (empty when the placement looks right) for a hull in ship axes:
//  - draft (deepest point below z = 0) against principal.d, within 5%;
//  - displacement volume against principal.displacement, within 5% (when given);
//  - the underwater body's x extent against 0..Lpp (at most 10% Lpp beyond);
//  - bow direction: a ship's waterplane is fuller aft than forward (a
//    transom or a full stern against a fine entrance), so its centre of
//    flotation lies aft of, or within 1% Lpp ahead of, midship. A centre of
//    flotation more than 2% Lpp ahead of midship, together with the centre of
//    buoyancy ahead of midship, means the bow and stern are probably swapped.
std::vector<std::string> CheckPlacement(const Hydrostatics& h, const HullPlacement& placement);

}  // namespace kelvin::cfd
