#include "phones/phone_seq.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>

#include "core/error.h"
#include "io/atomic_file.h"

namespace glossa::phones {

const std::vector<std::string>& arpabet() {
  static const std::vector<std::string> set = {
      "AA", "AE", "AH", "AO", "AW", "AY", "B", "CH", "D", "DH", "EH", "ER", "EY", "F",
      "G",  "HH", "IH", "IY", "JH", "K",  "L", "M",  "N", "NG", "OW", "OY", "P",  "R",
      "S",  "SH", "T",  "TH", "UH", "UW", "V", "W",  "Y", "Z",  "ZH", "SIL"};
  return set;
}

bool is_arpabet(std::string_view phone) {
  const auto& s = arpabet();
  return std::find(s.begin(), s.end(), phone) != s.end();
}

bool is_vowel(std::string_view p) {
  static const std::vector<std::string_view> v = {"AA", "AE", "AH", "AO", "AW", "AY", "EH", "ER",
                                                  "EY", "IH", "IY", "OW", "OY", "UH", "UW"};
  return std::find(v.begin(), v.end(), p) != v.end();
}

std::string normalize_phone(std::string_view symbol) {
  std::string s;
  for (char c : symbol)
    if (!std::isdigit(static_cast<unsigned char>(c)))
      s += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  if (s.empty()) return "";
  if (s == "SIL" || s == "SP" || s == "PAU" || s == "<SIL>" || s == "<S>" || s == "</S>" ||
      (s.size() > 2 && s.front() == '+' && s.back() == '+'))
    return "SIL";
  return is_arpabet(s) ? s : "";
}

void validate(const PhoneSeq& seq, const std::string& what) {
  double prev_end = -std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < seq.size(); ++i) {
    const auto& p = seq[i];
    if (!is_arpabet(p.phone))
      throw Error(fmt::format("{}: phone {} '{}' is not an ARPAbet symbol", what, i + 1, p.phone));
    if (!std::isfinite(p.start) || !std::isfinite(p.end) || p.start < 0 || p.end < p.start)
      throw Error(fmt::format("{}: phone {} '{}' has bad times {}..{}", what, i + 1, p.phone,
                              p.start, p.end));
    if (p.start < prev_end - 1e-6)
      throw Error(fmt::format("{}: phone {} '{}' starts at {} before the previous one ends ({})",
                              what, i + 1, p.phone, p.start, prev_end));
    prev_end = p.end;
  }
}

PhoneSeq read_phone_file(const std::string& path) {
  std::istringstream in(io::read_file(path));
  PhoneSeq seq;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ls(line);
    TimedPhone p;
    std::string sym, extra;
    if (!(ls >> p.start >> p.end >> sym) || (ls >> extra))
      throw file_error(path, fmt::format("line {}: expected 'start end PHONE'", n));
    p.phone = normalize_phone(sym);
    if (p.phone.empty())
      throw file_error(path, fmt::format("line {}: '{}' is not an ARPAbet phone", n, sym));
    seq.push_back(std::move(p));
  }
  validate(seq, path);
  return seq;
}

void write_phone_file(const std::string& path, const PhoneSeq& seq) {
  std::string out = "# start end phone (seconds, ARPAbet)\n";
  for (const auto& p : seq) out += fmt::format("{:.3f} {:.3f} {}\n", p.start, p.end, p.phone);
  io::write_file_atomic(path, out);
}

}  // namespace glossa::phones
