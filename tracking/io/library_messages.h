#pragma once
// OpenCV's codecs print their own failures on std::cerr ("imcount_('stack.tif'): can't read
// header: OpenCV(4.6.0) ./modules/imgcodecs/...: error: (-2:Unspecified error) in function
// 'readData'" and then "> Unsupported number of channels ..." lines), in their words and over
// several lines, where dimerlab's messages are one line naming the file. A codec call made on a
// thread inside a CerrToString scope writes that text into the scope's string instead; other
// threads' std::cerr is untouched, so frames decoded in parallel keep their messages apart.
#include <string>

namespace dimer::tracking {

class CerrToString {
 public:
  explicit CerrToString(std::string* sink);  // sink: appended to, on this thread only
  ~CerrToString();
  CerrToString(const CerrToString&) = delete;
  CerrToString& operator=(const CerrToString&) = delete;

 private:
  std::string* previous_;
};

// One line from a library's message: OpenCV's exception text reduced to what failed and why
// ("can't read header: Unsupported number of channels"); other text with its lines joined by
// "; ". "" for empty or blank text.
std::string OneLineLibraryMessage(const std::string& text);

}  // namespace dimer::tracking
