/// Names of the knee's parts as segmentation tools and atlases spell them.

#include "stages/anatomy/part_names.hpp"

#include <gtest/gtest.h>

using namespace ligsim::anatomy;

TEST(PartNames, TheKneesPartsUnderTheirUsualNames)
{
  const std::vector<std::pair<std::string, KneePart>> named = {
      {"femur", KneePart::femur},
      {"Femur", KneePart::femur},
      {"VH_F_femur_L", KneePart::femur},
      {"Left femur bone", KneePart::femur},
      {"tibia", KneePart::tibia},
      {"VH_M_tibia_R", KneePart::tibia},
      {"fibula", KneePart::fibula},
      {"Patella", KneePart::patella},
      {"tibial_collateral_ligament", KneePart::mcl},
      {"VH_F_left_tibial_collateral_ligament", KneePart::mcl},
      {"VH_M_right_tibial_collaterial_ligament", KneePart::mcl}, // the atlas' spelling
      {"MCL", KneePart::mcl},
      {"sMCL", KneePart::mcl},
      {"Medial collateral lig.", KneePart::mcl},
      {"MedialCollateralLigament", KneePart::mcl},
      {"fibular_collateral_ligament", KneePart::lcl},
      {"LCL", KneePart::lcl},
      {"FCL", KneePart::lcl},
      {"lateral collateral ligament", KneePart::lcl},
      {"anterior_cruciate_ligament", KneePart::acl},
      {"VH_F_anterior_cruciate_ligament_of_knee_L", KneePart::acl},
      {"ACL", KneePart::acl},
      {"Posterior Cruciate Ligament", KneePart::pcl},
      {"PCL_R", KneePart::pcl},
      {"femoral_cartilage", KneePart::femoral_cartilage},
      {"medial_tibial_cartilage", KneePart::tibial_cartilage},
      {"lateral tibial cartilage", KneePart::tibial_cartilage},
      {"patellar_cartilage", KneePart::patellar_cartilage},
      {"lateral_meniscus", KneePart::meniscus},
      {"VH_F_meniscus_L", KneePart::meniscus},
  };
  for (const auto& [name, part] : named) {
    const auto found = recognise_part(name);
    ASSERT_TRUE(found.has_value()) << name;
    EXPECT_EQ(part_name(*found), part_name(part)) << name;
  }
}

TEST(PartNames, PartsOfPartsAndOtherLigamentsAreNotGuessed)
{
  for (const char* name :
       {"VH_F_medial_condyle_of_left_femur_inf", "VH_F_lateral_epicondylar_enthesis_L",
        "VH_F_intercondylar_fossa_L", "VH_F_anterolateral_ligament_of_knee_L",
        "VH_F_patellar_ligament_L", "VH_F_articular_cartilage_of_knee_L", "deep MCL", "Background",
        "label_7", "", "tibial plateau"})
    EXPECT_FALSE(recognise_part(name).has_value()) << name;
}

TEST(PartNames, LigamentsAndBonesAreToldApart)
{
  for (const KneePart part : {KneePart::mcl, KneePart::lcl, KneePart::acl, KneePart::pcl}) {
    EXPECT_TRUE(is_ligament(part));
    EXPECT_FALSE(is_bone(part));
  }
  for (const KneePart part :
       {KneePart::femur, KneePart::tibia, KneePart::fibula, KneePart::patella})
    EXPECT_TRUE(is_bone(part));
  EXPECT_FALSE(is_bone(KneePart::meniscus));
  EXPECT_FALSE(is_ligament(KneePart::femoral_cartilage));
}
