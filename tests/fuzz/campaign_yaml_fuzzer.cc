// Captive campaign files.
#include "data/schema/campaign_file.h"
#include "data/schema/config.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  kelvin::fuzz::ExpectInputError([&] {
    const auto root = kelvin::data::ConfigNode::LoadString(kelvin::fuzz::Text(data, size), "campaign.yaml");
    kelvin::data::LoadCampaignFile(root, "/nonexistent/campaign.yaml");
  });
  return 0;
}
