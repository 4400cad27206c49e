#include "vtkCausticsFileText.h"

namespace caustics
{
namespace text
{
std::string Printable(std::string_view text, std::size_t limit)
{
  static const char* const hex = "0123456789abcdef";
  std::string out;
  std::size_t i = 0;
  for (; i < text.size(); ++i)
  {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    const bool printable = c >= 0x20 && c < 0x7f;
    if (out.size() + (printable ? 1 : 4) > limit)
    {
      break;
    }
    if (printable)
    {
      out.push_back(static_cast<char>(c));
    }
    else
    {
      out += "\\x";
      out.push_back(hex[c >> 4]);
      out.push_back(hex[c & 15]);
    }
  }
  if (i < text.size())
  {
    out += "...";
  }
  return out;
}

std::string Quote(std::string_view text)
{
  return "'" + Printable(text, QuoteLength) + "'";
}
}
}
