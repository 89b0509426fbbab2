#include "stages/anatomy/part_names.hpp"

#include <algorithm>
#include <cctype>
#include <set>
#include <vector>

namespace ligsim::anatomy {

namespace {

/// Lower-case words of `name`: split at separators and at a lower-to-upper case change
/// after a word of two letters or more ("TibialCollateral" -> tibial, collateral; "sMCL" stays).
std::vector<std::string> words(const std::string& name)
{
  std::vector<std::string> result;
  std::string word;
  const auto finish = [&] {
    if (!word.empty())
      result.push_back(word);
    word.clear();
  };
  for (std::size_t i = 0; i < name.size(); ++i) {
    const auto c = static_cast<unsigned char>(name[i]);
    if (!std::isalnum(c)) {
      finish();
      continue;
    }
    if (std::isupper(c) && word.size() > 1 && std::islower(static_cast<unsigned char>(name[i - 1])))
      finish();
    word += static_cast<char>(std::tolower(c));
  }
  finish();
  return result;
}

/// Words that say nothing of which part it is: the side, "bone", an atlas' subject prefix.
std::vector<std::string> meaningful(std::vector<std::string> w)
{
  if (w.size() >= 2 && w[0] == "vh" && (w[1] == "f" || w[1] == "m"))
    w.erase(w.begin(), w.begin() + 2);
  static const std::set<std::string> noise = {
      "left", "right", "l",       "r",     "lt",   "rt",  "bone", "bones",  "of",      "the",
      "knee", "seg",   "segment", "label", "mask", "and", "os",   "distal", "proximal"};
  w.erase(std::remove_if(w.begin(), w.end(), [](const std::string& s) { return noise.count(s); }),
          w.end());
  return w;
}

bool starts(const std::string& word, const char* prefix)
{
  return word.rfind(prefix, 0) == 0;
}

bool any(const std::vector<std::string>& w, std::initializer_list<const char*> prefixes)
{
  return std::any_of(w.begin(), w.end(), [&](const std::string& s) {
    return std::any_of(prefixes.begin(), prefixes.end(),
                       [&](const char* p) { return starts(s, p); });
  });
}

/// Every word is one of `allowed` (by prefix).
bool only(const std::vector<std::string>& w, std::initializer_list<const char*> allowed)
{
  return std::all_of(w.begin(), w.end(), [&](const std::string& s) {
    return std::any_of(allowed.begin(), allowed.end(), [&](const char* p) { return starts(s, p); });
  });
}

std::optional<KneePart> cartilage(const std::vector<std::string>& w)
{
  if (any(w, {"femor", "femur", "condyl", "trochle"}))
    return KneePart::femoral_cartilage;
  if (any(w, {"tibia", "plateau"}))
    return KneePart::tibial_cartilage;
  if (any(w, {"patell"}))
    return KneePart::patellar_cartilage;
  return std::nullopt; // "articular cartilage of knee": which bone's is not said
}

std::optional<KneePart> ligament(const std::vector<std::string>& w)
{
  // Besides the words naming it, a ligament's name may say "ligament" and "superficial".
  const auto named = [&](std::initializer_list<const char*> words_of_it) {
    std::vector<std::string> rest;
    for (const std::string& s : w)
      if (!std::any_of(words_of_it.begin(), words_of_it.end(),
                       [&](const char* p) { return starts(s, p); }))
        rest.push_back(s);
    return only(rest, {"lig", "superficial"});
  };
  const bool collateral = any(w, {"collat", "coll"});
  const bool cruciate = any(w, {"cruc"});
  if (any(w, {"acl"}) && named({"acl"}))
    return KneePart::acl;
  if (any(w, {"pcl"}) && named({"pcl"}))
    return KneePart::pcl;
  if (any(w, {"mcl", "smcl"}) && named({"mcl", "smcl"}))
    return KneePart::mcl;
  if (any(w, {"lcl", "fcl"}) && named({"lcl", "fcl"}))
    return KneePart::lcl;
  if (cruciate && any(w, {"ant"}) && named({"ant", "cruc"}))
    return KneePart::acl;
  if (cruciate && any(w, {"post"}) && named({"post", "cruc"}))
    return KneePart::pcl;
  if (collateral && any(w, {"medial", "tibial"}) && named({"medial", "tibial", "coll"}))
    return KneePart::mcl;
  if (collateral && any(w, {"lateral", "fibular"}) && named({"lateral", "fibular", "coll"}))
    return KneePart::lcl;
  return std::nullopt;
}

std::optional<KneePart> bone(const std::vector<std::string>& w)
{
  if (w.size() != 1)
    return std::nullopt; // "medial condyle of femur" is a part of the femur, not the femur
  const std::string& s = w[0];
  if (s == "femur" || s == "femoral")
    return KneePart::femur;
  if (s == "tibia" || s == "tibial")
    return KneePart::tibia;
  if (s == "fibula" || s == "fibular")
    return KneePart::fibula;
  if (s == "patella" || s == "patellar")
    return KneePart::patella;
  return std::nullopt;
}

} // namespace

std::optional<KneePart> recognise_part(const std::string& name)
{
  const std::vector<std::string> w = meaningful(words(name));
  if (w.empty())
    return std::nullopt;
  if (any(w, {"menisc"}))
    return only(w, {"menisc", "medial", "lateral"}) ? std::optional(KneePart::meniscus)
                                                    : std::nullopt;
  if (any(w, {"cartilag"}))
    return cartilage(w);
  if (auto found = ligament(w))
    return found;
  return bone(w);
}

std::string part_name(KneePart part)
{
  switch (part) {
  case KneePart::femur:
    return "femur";
  case KneePart::tibia:
    return "tibia";
  case KneePart::fibula:
    return "fibula";
  case KneePart::patella:
    return "patella";
  case KneePart::mcl:
    return "MCL";
  case KneePart::lcl:
    return "LCL";
  case KneePart::acl:
    return "ACL";
  case KneePart::pcl:
    return "PCL";
  case KneePart::femoral_cartilage:
    return "femoral_cartilage";
  case KneePart::tibial_cartilage:
    return "tibial_cartilage";
  case KneePart::patellar_cartilage:
    return "patellar_cartilage";
  case KneePart::meniscus:
    return "meniscus";
  }
  return "";
}

bool is_ligament(KneePart part)
{
  return part == KneePart::mcl || part == KneePart::lcl || part == KneePart::acl ||
         part == KneePart::pcl;
}

bool is_bone(KneePart part)
{
  return part == KneePart::femur || part == KneePart::tibia || part == KneePart::fibula ||
         part == KneePart::patella;
}

} // namespace ligsim::anatomy
