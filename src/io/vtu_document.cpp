#include "io/vtu_document.h"

#include <algorithm>
#include <charconv>
#include <cstring>
#include <string_view>

#include "common/error.h"
#include "common/hash.h"
#include "io_core/text_scan.h"

namespace sm::io {
namespace {

std::string_view asText(std::span<const uint8_t> b) {
  return {reinterpret_cast<const char*>(b.data()), b.size()};
}

// Guards every tuples x components x size product against overflow (and absurd sizes).
constexpr uint64_t kMaxBytes = uint64_t(1) << 60;

}  // namespace

void checkPieceIsNotAnIndex(std::span<const uint8_t> bytes, const std::string& source) {
  const std::string_view head(reinterpret_cast<const char*>(bytes.data()),
                              std::min<size_t>(bytes.size(), 4096));
  const size_t tag = head.find("<VTKFile");
  if (tag == std::string_view::npos) return;
  const std::string_view attrs = head.substr(tag, head.find('>', tag) - tag);
  if (attrs.find("type=\"PUnstructuredGrid\"") != std::string_view::npos ||
      attrs.find("type='PUnstructuredGrid'") != std::string_view::npos)
    throw FileError(source, "is itself a .pvtu index, named as a piece: pieces must be .vtu files");
}

VtuDocument::VtuDocument(FileBytes& bytes, std::string source, const char* type, unsigned threads,
                         StopRequested stop)
    : source_(std::move(source)) {
  format_.threads = threads;
  format_.stop = std::move(stop);
  parse(bytes, type);
}

void VtuDocument::parse(FileBytes& bytes, const char* type) {
  std::string_view text = asText(bytes.span());
  size_t tag = text.find("<AppendedData");
  pugi::xml_parse_result result;
  if (tag == std::string_view::npos) {
    result = doc_.load_buffer_inplace(bytes.writableData(), bytes.size());
  } else {
    // Parse a copy of the XML before the appended data, closed off by hand; the data itself is
    // located from the tag: it starts after the '_' that follows it.
    size_t close = text.find('>', tag);
    if (close == std::string_view::npos)
      throw FileError(source_, "the <AppendedData> tag is not closed");
    std::string_view tagText = text.substr(tag, close - tag);
    bool selfClosing = !tagText.empty() && tagText.back() == '/';
    if (selfClosing) tagText.remove_suffix(1);
    xmlCopy_.reserve(tag + tagText.size() + 16);
    xmlCopy_.append(text.substr(0, tag)).append(tagText).append("/></VTKFile>");
    result = doc_.load_buffer_inplace(xmlCopy_.data(), xmlCopy_.size());
    if (!selfClosing) {
      size_t p = close + 1;
      while (p < text.size() && isSpace(text[p])) ++p;
      if (p >= text.size() || text[p] != '_')
        throw FileError(source_, "appended data does not start with '_'");
      hasAppended_ = true;
      appended_ = bytes.span().subspan(p + 1);
    }
  }
  if (!result)
    throw FileError(source_, "is not valid XML (", result.description(), " at byte ", result.offset,
                    ")");
  pugi::xml_node root = doc_.document_element();
  if (std::strcmp(root.name(), "VTKFile") != 0)
    throw FileError(source_, "is not a VTK XML file (its root element is <", printable(root.name()),
                    ">)");
  std::string_view fileType = root.attribute("type").value();
  if (fileType != type) {
    if (fileType == "PUnstructuredGrid")
      throw FileError(source_, "is a parallel unstructured grid: give it the .pvtu extension");
    throw FileError(source_, "is a VTK XML '", printable(fileType), "' file, expected '", type,
                    "'");
  }
  readFormat(root);
  if (hasAppended_) {
    pugi::xml_node app = root.child("AppendedData");
    std::string_view enc = app.attribute("encoding").value();
    if (enc == "base64")
      appendedBase64_ = true;
    else if (enc != "raw")
      throw FileError(source_, "appended data has unknown encoding '", printable(enc), "'");
  }
}

void VtuDocument::readFormat(pugi::xml_node root) {
  std::string_view order = root.attribute("byte_order").value();
  if (order == "BigEndian")
    format_.swap = needsSwap(true);
  else if (order.empty() || order == "LittleEndian")
    format_.swap = needsSwap(false);
  else
    throw FileError(source_, "unknown byte_order '", printable(order), "'");
  std::string_view header = root.attribute("header_type").value();
  if (header == "UInt64")
    format_.header64 = true;
  else if (!header.empty() && header != "UInt32")
    throw FileError(source_, "unknown header_type '", printable(header), "'");
  std::string_view comp = root.attribute("compressor").value();
  if (comp == "vtkZLibDataCompressor")
    format_.compressor = Compressor::ZLib;
  else if (comp == "vtkLZ4DataCompressor")
    format_.compressor = Compressor::LZ4;
  else if (comp == "vtkLZMADataCompressor")
    format_.compressor = Compressor::LZMA;
  else if (!comp.empty())
    throw FileError(source_, "uses the unknown compressor '", printable(comp), "'");
}

uint64_t VtuDocument::count(pugi::xml_node node, const char* attribute) const {
  pugi::xml_attribute a = node.attribute(attribute);
  if (!a) throw FileError(source_, "<", node.name(), "> has no ", attribute);
  std::string_view v = a.value();
  uint64_t n = 0;
  auto [p, ec] = std::from_chars(v.data(), v.data() + v.size(), n);
  while (p < v.data() + v.size() && isSpace(*p)) ++p;  // VTK pads these with spaces
  if (ec != std::errc() || p != v.data() + v.size() || n > kMaxBytes)
    throw FileError(source_, "<", node.name(), "> has ", attribute, "=\"", printable(v),
                    "\", not a count");
  return n;
}

uint32_t VtuDocument::components(pugi::xml_node node, const std::string& what) const {
  if (!node.attribute("NumberOfComponents")) return 1;
  uint64_t n = count(node, "NumberOfComponents");
  if (n < 1 || n > 4096)
    throw FileError(source_, what, ": NumberOfComponents=", n, " is out of range");
  return static_cast<uint32_t>(n);
}

NumericArray VtuDocument::decode(pugi::xml_node node, uint64_t tuples, const std::string& what,
                                 uint32_t wantComponents, Length length) const {
  throwIfStopped(format_.stop, source_);
  std::string_view typeName = node.attribute("type").value();
  auto type = scalarTypeFromXml(typeName);
  if (!type) throw FileError(source_, what, ": unsupported array type '", printable(typeName), "'");
  const uint32_t comps = components(node, what);
  if (wantComponents && comps != wantComponents)
    throw FileError(source_, what, ": has ", comps, " components, expected ", wantComponents);
  const uint64_t size = scalarSize(*type);
  if (tuples > kMaxBytes / comps / size)
    throw FileError(source_, what, ": ", tuples, " tuples is an impossible size");
  const uint64_t bytes = tuples * comps * size;

  std::string_view format = node.attribute("format").value();
  if (format == "ascii") return decodeAscii(node, *type, comps, tuples, what, length);
  PayloadSource src = PayloadSource::raw({}, 0);
  if (format == "binary") {
    src = PayloadSource::base64(node.child_value(), 0);
  } else if (format == "appended") {
    if (!hasAppended_)
      throw FileError(source_, what, ": refers to appended data, but there is none");
    uint64_t offset = count(node, "offset");
    if (offset > appended_.size())
      throw FileError(source_, what, ": offset ", offset, " is past the end of the appended data");
    src = appendedBase64_ ? PayloadSource::base64(asText(appended_), offset)
                          : PayloadSource::raw(appended_, offset);
  } else {
    throw FileError(source_, what, ": unknown format '", printable(format), "'");
  }
  Payload p = readPayload(src, format_, bytes, source_, what, length);
  if (p.bytes % (comps * size) != 0)
    throw FileError(source_, what, ": holds ", p.bytes, " bytes, not a whole number of ", comps,
                    "-component ", typeName, " tuples");
  tuples = p.bytes / (comps * size);
  if (p.storage.data())
    return NumericArray::owned(*type, comps, tuples, std::move(p.storage), format_.swap);
  return NumericArray::view(*type, comps, tuples, p.data, format_.swap);
}

uint64_t VtuDocument::encodedDigest(pugi::xml_node node) const {
  Hasher h;
  for (pugi::xml_attribute a : root().attributes()) h.str(a.name()).str(a.value());
  for (pugi::xml_attribute a : node.attributes())
    if (std::strcmp(a.name(), "offset") != 0) h.str(a.name()).str(a.value());
  if (std::string_view(node.attribute("format").value()) != "appended")
    return h.str(node.child_value()).digest();
  const pugi::xml_attribute at = node.attribute("offset");
  const uint64_t offset = at.as_ullong(~uint64_t(0));
  if (!hasAppended_ || offset >= appended_.size()) return 0;
  // The array's bytes end where the next one's begin (or with the file): its own header, which
  // says where it ends, is part of what is compared.
  uint64_t end = appended_.size();
  for (pugi::xpath_node n : doc_.select_nodes("//DataArray[@format='appended']")) {
    const uint64_t o = n.node().attribute("offset").as_ullong(0);
    if (o > offset && o < end) end = o;
  }
  return h.bytes(appended_.data() + offset, end - offset).digest();
}

NumericArray VtuDocument::decodeAscii(pugi::xml_node node, ScalarType type, uint32_t comps,
                                      uint64_t tuples, const std::string& what,
                                      Length length) const {
  std::string_view text = node.child_value();
  if (length == Length::AtLeast) {  // as many whole tuples as the text holds
    uint64_t values = 0;
    for (TextCursor count(text); !count.token().empty();) ++values;
    if (values % comps != 0)
      throw FileError(source_, what, ": holds ", values, " values, not a whole number of ", comps,
                      "-component tuples");
    if (values / comps > tuples) tuples = values / comps;
  }
  const uint64_t n = tuples * comps;
  if (n > maxNumbersInText(text.size()))
    throw FileError(source_, what, ": declares ", n, " values but its text holds at most ",
                    maxNumbersInText(text.size()));
  TextCursor cursor(text);
  ByteBuffer buf = ByteBuffer::allocate(std::max<uint64_t>(n, 1) * 8);
  ScalarType stored;
  if (isFloatType(type)) {
    stored = ScalarType::Float64;
    scanNumbers(cursor, reinterpret_cast<double*>(buf.data()), n, source_, what);
  } else if (type == ScalarType::UInt64) {
    stored = ScalarType::UInt64;
    scanNumbers(cursor, reinterpret_cast<uint64_t*>(buf.data()), n, source_, what);
  } else {
    stored = ScalarType::Int64;
    scanNumbers(cursor, reinterpret_cast<int64_t*>(buf.data()), n, source_, what);
  }
  if (!cursor.atEnd())
    throw FileError(source_, what, ": has more than the ", n, " values expected");
  return NumericArray::owned(stored, comps, tuples, std::move(buf), false);
}

}  // namespace sm::io
