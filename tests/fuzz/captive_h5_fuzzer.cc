// Captive campaigns as HDF5 (written to a scratch file: the HDF5 library
// opens files by name).
#include "data/schema/captive_io.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = kelvin::fuzz::ScratchFile("campaign.h5", data, size);
  kelvin::fuzz::ExpectInputError([&] { kelvin::data::ReadCampaignH5(path); });
  return 0;
}
