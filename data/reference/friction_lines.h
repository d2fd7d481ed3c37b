// Friction lines of naval hydrodynamics shared by the stages: the ITTC-1957
// model-ship correlation line, used by the simulator to scale R0' between
// model and full scale and by the CFD for first-cell heights and as the
// reference of the flat-plate and double-body verification cases.
#pragma once

namespace kelvin::data {

// ITTC-1957 model-ship correlation line C_F = 0.075 / (log10 Re - 2)^2.
// Throws kelvin::ModelError for a Reynolds number that is not finite or not
// above 100, where log10 Re - 2 <= 0 and the line has no meaning.
double Ittc57FrictionCoefficient(double reynolds);

}  // namespace kelvin::data
