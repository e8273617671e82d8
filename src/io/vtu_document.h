// One VTK XML file (.vtu) as structure: the XML parsed without the appended data (raw bytes that
// are not XML and can be gigabytes), the binary format the file declares, and the decoding of
// its DataArray elements in every encoding (ascii, inline base64, appended raw or base64, each
// optionally zlib-compressed).
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include <pugixml.hpp>

#include "io/vtk_binary.h"
#include "io_core/file_bytes.h"
#include "io_core/numeric_array.h"

namespace sm::io {

// For a file named as a .pvtu's piece: throws a FileError naming `source` when the <VTKFile> tag
// near the start of `bytes` says type="PUnstructuredGrid" (a .pvtu index), without parsing the
// document. (VtuDocument's own advice for such a file, "give it the .pvtu extension", is for a
// file the user named, not for a piece.)
void checkPieceIsNotAnIndex(std::span<const uint8_t> bytes, const std::string& source);

class VtuDocument {
 public:
  // Parses bytes (in place: bytes must outlive the document). `type` is the VTKFile type this
  // reader expects ("UnstructuredGrid"); throws sm::FileError for anything else.
  // `threads` inflate compressed arrays; `stop` is asked before each array and compressed block.
  VtuDocument(FileBytes& bytes, std::string source, const char* type, unsigned threads = 0,
              StopRequested stop = {});
  VtuDocument(const VtuDocument&) = delete;
  VtuDocument& operator=(const VtuDocument&) = delete;

  pugi::xml_node root() const { return doc_.document_element(); }
  const std::string& source() const { return source_; }

  // Decodes a DataArray holding `tuples` tuples (Length::AtLeast: that many or more, all of them
  // returned); `components` 0 accepts any count. The result views the file where the data is raw
  // and uncompressed.
  NumericArray decode(pugi::xml_node dataArray, uint64_t tuples, const std::string& what,
                      uint32_t components = 0, Length length = Length::Exact) const;
  // A digest of how a DataArray is stored: the file's format attributes, the array's attributes
  // and its encoded bytes (text, or appended bytes up to the next array's), none decoded. Arrays
  // with equal digests decode to the same values (equal values may be stored differently). 0 when
  // its appended offset is not valid (decode names that).
  uint64_t encodedDigest(pugi::xml_node dataArray) const;
  // NumberOfComponents (1 when absent), checked.
  uint32_t components(pugi::xml_node dataArray, const std::string& what) const;
  // A required non-negative integer attribute.
  uint64_t count(pugi::xml_node node, const char* attribute) const;

 private:
  void parse(FileBytes& bytes, const char* type);
  void readFormat(pugi::xml_node root);
  NumericArray decodeAscii(pugi::xml_node node, ScalarType type, uint32_t comps, uint64_t tuples,
                           const std::string& what, Length length) const;

  std::string source_;
  std::string xmlCopy_;  // the XML part, when the file has appended data
  pugi::xml_document doc_;
  BinaryFormat format_;
  bool hasAppended_ = false;
  bool appendedBase64_ = false;
  std::span<const uint8_t> appended_;  // after the '_' marker
};

}  // namespace sm::io
