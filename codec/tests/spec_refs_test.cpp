// Every "§N" or "§N.M" cited in codec/src and codec/include names a heading of spec/prm-format.md, and every
// numbered heading of the implemented sections is cited somewhere in the code (STYLE.md: spec numbers mirrored in
// code).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

namespace {

std::string slurp(const std::filesystem::path& p) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

TEST(SpecReferences, CitedSectionsExist) {
  const std::filesystem::path root = PRM_SOURCE_DIR;
  const std::string spec = slurp(root / "spec" / "prm-format.md");
  ASSERT_FALSE(spec.empty());
  std::set<std::string> headings;
  const std::regex heading(R"(^#{2,4} ([0-9]+(\.[0-9]+)*)\.? )", std::regex::multiline);
  for (auto it = std::sregex_iterator(spec.begin(), spec.end(), heading); it != std::sregex_iterator(); ++it)
    headings.insert((*it)[1]);
  std::set<std::string> cited;
  const std::regex ref("§([0-9]+(\\.[0-9]+)*)");
  for (const char* dir : {"codec/src", "codec/include/prm"}) {
    for (const auto& e : std::filesystem::directory_iterator(root / dir)) {
      const std::string text = slurp(e.path());
      for (auto it = std::sregex_iterator(text.begin(), text.end(), ref); it != std::sregex_iterator(); ++it) {
        std::string s = (*it)[1];
        EXPECT_TRUE(headings.count(s)) << e.path().filename() << " cites §" << s << ", which the spec does not have";
        cited.insert(s);
      }
    }
  }
  // The implemented numbered subsections (3.x, 4.x, 5.x, 6.x, 10.x) are each cited by the code.
  for (const std::string& h : headings) {
    const bool implemented = h.find('.') != std::string::npos &&
                             (h[0] == '3' || h[0] == '4' || h[0] == '5' || h[0] == '6' || h.rfind("10.", 0) == 0);
    const bool informative = h == "3.6" || h == "5.8" || h == "6.4.9" || h == "6.9";  // examples, rationale
    if (implemented && !informative) {
      EXPECT_TRUE(cited.count(h)) << "spec §" << h << " is cited nowhere in codec/";
    }
  }
}

}  // namespace
