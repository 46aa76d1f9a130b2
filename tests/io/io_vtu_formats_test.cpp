// The VTK XML layer (lib/io/vtk_xml.h) through the tet reader: every format VTK
// writes (committed files made by tests/data/make_vtk_variants.py) reads back
// the same mesh as the ASCII original; the base64 and zlib pieces on their own;
// and malformed or truncated input is an InputError naming the place.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <cstring>
#include <sstream>

#include "core/error.h"
#include "io/file_bytes.h"
#include "io/vtk_xml.h"
#include "io/vtu_reader.h"

namespace polydual {
namespace {

using testing::HasSubstr;
const std::string kData = POLYDUAL_TEST_DATA;

const char* const kVariants[] = {"cube5_vtk_appended_raw.vtu",  "cube5_vtk_appended_raw_zlib.vtu",
                                 "cube5_vtk_appended_b64.vtu",  "cube5_vtk_appended_b64_zlib.vtu",
                                 "cube5_vtk_binary_zlib.vtu",   "cube5_vtk_binary_zlib64.vtu",
                                 "cube5_bin.vtu",               "cube5_bin32.vtu"};

void expect_same_soup(const TetSoup& a, const TetSoup& b) {
  ASSERT_EQ(a.points.size(), b.points.size());
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    EXPECT_EQ(a.points[i].x, b.points[i].x) << i;
    EXPECT_EQ(a.points[i].y, b.points[i].y) << i;
    EXPECT_EQ(a.points[i].z, b.points[i].z) << i;
  }
  EXPECT_EQ(a.tets, b.tets);
  EXPECT_EQ(a.tet_region, b.tet_region);
  ASSERT_EQ(a.triangles.size(), b.triangles.size());
  for (std::size_t i = 0; i < a.triangles.size(); ++i) {
    EXPECT_EQ(a.triangles[i].v, b.triangles[i].v) << i;
    EXPECT_EQ(a.triangles[i].tag, b.triangles[i].tag) << i;
  }
}

std::string error_of(const std::string& bytes) {
  try {
    read_vtu(bytes, "t.vtu");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(IoVtuFormats, EveryVtkVariantReadsTheAsciiMesh) {
  const TetSoup ascii = read_vtu_file(kData + "/cube5.vtu");
  ASSERT_EQ(ascii.tets.size(), 5u);
  ASSERT_EQ(ascii.triangles.size(), 16u);
  for (const char* name : kVariants) {
    SCOPED_TRACE(name);
    const TetSoup s = read_vtu_file(kData + "/" + name);
    if (std::string(name).find("cube5_vtk") == 0) expect_same_soup(ascii, s);
    else EXPECT_EQ(s.tets, ascii.tets);  // the make_binary.py files carry no triangles
  }
}

TEST(IoVtuFormats, TheVariantsReallyUseTheirFormats) {
  // Guards the data files: each holds the format its name says.
  auto has = [](const char* name, const char* needle) {
    return io::read_file_bytes(kData + "/" + name).find(needle) != std::string::npos;
  };
  EXPECT_TRUE(has("cube5_vtk_appended_raw.vtu", "encoding=\"raw\""));
  EXPECT_TRUE(has("cube5_vtk_appended_b64.vtu", "encoding=\"base64\""));
  EXPECT_TRUE(has("cube5_vtk_appended_raw_zlib.vtu", "vtkZLibDataCompressor"));
  EXPECT_TRUE(has("cube5_vtk_appended_raw_zlib.vtu", "header_type=\"UInt32\""));
  EXPECT_TRUE(has("cube5_vtk_binary_zlib64.vtu", "header_type=\"UInt64\""));
  EXPECT_TRUE(has("cube5_vtk_binary_zlib.vtu", "format=\"binary\""));
}

// Every prefix of every variant is an InputError (or, for a prefix that ends
// only after </VTKFile>, the mesh): never a crash or another exception.
TEST(IoVtuFormats, EveryTruncationIsAnInputError) {
  for (const char* name : kVariants) {
    const std::string bytes = io::read_file_bytes(kData + "/" + name);
    const std::size_t end = bytes.rfind("</VTKFile>");
    for (std::size_t n = 0; n < end; ++n) {
      try {
        read_vtu(std::string_view(bytes).substr(0, n), name);
        ADD_FAILURE() << name << " cut at " << n << " read without error";
      } catch (const InputError&) {
      }
    }
  }
}

// Every single-byte corruption of the compressed and appended data is an
// InputError or a mesh (a flipped bit in a coordinate is still a mesh).
TEST(IoVtuFormats, EveryByteFlipIsAnInputErrorOrAMesh) {
  for (const char* name : {"cube5_vtk_appended_raw_zlib.vtu", "cube5_vtk_appended_b64_zlib.vtu"}) {
    const std::string bytes = io::read_file_bytes(kData + "/" + name);
    for (std::size_t i = bytes.find('_'); i < bytes.size(); ++i) {
      std::string bad = bytes;
      bad[i] = static_cast<char>(bad[i] ^ 0x5a);
      try {
        read_vtu(bad, name);
      } catch (const InputError&) {
      }
    }
  }
}

TEST(IoVtuFormats, Base64ReaderAcrossSeparatelyPaddedStreams) {
  const std::string a = "\x01\x02\x03\x04", b = "hello, world";
  const std::string text = io::vtkxml::encode_base64(a) + "\n  " + io::vtkxml::encode_base64(b);
  io::vtkxml::Base64Reader r(text);
  std::string out;
  EXPECT_EQ(r.read(3, out), 3u);
  EXPECT_EQ(r.read(100, out), a.size() + b.size() - 3);
  EXPECT_EQ(out, a + b);
  io::vtkxml::Base64Reader bad("AA=A");
  EXPECT_EQ(bad.read(3, out), std::nullopt);
  io::vtkxml::Base64Reader junk("AB$D");
  EXPECT_EQ(junk.read(3, out), std::nullopt);
}

TEST(IoVtuFormats, ZlibHeaderLayout) {
  const std::string data(100, 'x');
  const auto z = io::vtkxml::zlib_compress(data, 6, false, 64);
  ASSERT_EQ(z.header.size(), 4u * 5);  // 2 blocks: count, size, last, 2 sizes
  std::uint32_t w[5];
  std::memcpy(w, z.header.data(), sizeof w);
  EXPECT_EQ(w[0], 2u);
  EXPECT_EQ(w[1], 64u);
  EXPECT_EQ(w[2], 36u);
  EXPECT_EQ(w[3] + w[4], z.blocks.size());
}

// An inline zlib array for a one-point file: `header` words (UInt32) then blocks.
std::string one_point_zlib(const std::vector<std::uint32_t>& header, const std::string& blocks) {
  std::string h(reinterpret_cast<const char*>(header.data()), header.size() * 4);
  return R"(<VTKFile type="UnstructuredGrid" compressor="vtkZLibDataCompressor"><UnstructuredGrid>
<Piece NumberOfPoints="1" NumberOfCells="0"><Points>
<DataArray type="Float64" Name="P" NumberOfComponents="3" format="binary">)" +
         io::vtkxml::encode_base64(h) + io::vtkxml::encode_base64(blocks) +
         "</DataArray></Points><Cells><DataArray type=\"Int32\" Name=\"connectivity\"></DataArray>"
         "<DataArray type=\"Int32\" Name=\"offsets\"></DataArray><DataArray type=\"UInt8\" Name=\"types\">"
         "</DataArray></Cells></Piece></UnstructuredGrid></VTKFile>";
}

TEST(IoVtuFormats, CompressedArrayErrors) {
  const double xyz[3] = {1, 2, 3};
  const auto z = io::vtkxml::zlib_compress(std::string_view(reinterpret_cast<const char*>(xyz), 24), 9, false);
  const std::uint32_t csize = static_cast<std::uint32_t>(z.blocks.size());
  const std::string good = one_point_zlib({1, 24, 24, csize}, z.blocks);
  const io::vtkxml::VtkXml file(good, "t.vtu", "UnstructuredGrid");
  const std::vector<double> ok = file.reals(*file.find_array("Points"));
  ASSERT_EQ(ok.size(), 3u);
  EXPECT_EQ(ok[2], 3.0);
  EXPECT_THAT(error_of(good), HasSubstr("t.vtu: line 2: the file holds no tetrahedra (NumberOfCells is 0)"));
  EXPECT_THAT(error_of(one_point_zlib({1, 24, 24, csize + 5}, z.blocks)),
              HasSubstr("line 3: DataArray 'P': compressed block size"));
  EXPECT_THAT(error_of(one_point_zlib({1, 32, 32, csize}, z.blocks)),
              HasSubstr("DataArray 'P': zlib block 0 does not inflate to its 32 bytes"));
  EXPECT_THAT(error_of(one_point_zlib({1, 24, 24, csize}, std::string(csize, 'x'))),
              HasSubstr("zlib block 0 does not inflate"));
  EXPECT_THAT(error_of(one_point_zlib({1, 1u << 30, 1u << 30, csize}, z.blocks)),
              HasSubstr("zlib block 0 claims 1073741824 bytes from"));
  EXPECT_THAT(error_of(one_point_zlib({1000000, 24, 24}, z.blocks)),
              HasSubstr("compression header announces 1000000 blocks"));
  EXPECT_THAT(error_of(one_point_zlib({1, 24, 25, csize}, z.blocks)), HasSubstr("last block size 25 exceeds"));
  const auto z7 = io::vtkxml::zlib_compress(std::string(7, 'a'), 9, false);
  EXPECT_THAT(error_of(one_point_zlib({1, 7, 7, static_cast<std::uint32_t>(z7.blocks.size())}, z7.blocks)),
              HasSubstr("uncompressed size 7 is not a whole number of Float64"));
}

TEST(IoVtuFormats, AppendedArrayErrors) {
  std::string raw = io::read_file_bytes(kData + "/cube5_vtk_appended_raw.vtu");
  const std::size_t underscore = raw.find('_', raw.find("<AppendedData"));
  // Data cut short: the Points array (at offset 340) has 3 of its 8 header bytes.
  EXPECT_THAT(error_of(raw.substr(0, underscore + 1 + 343) + "\n</AppendedData></VTKFile>"),
              HasSubstr("t.vtu: byte " + std::to_string(underscore + 1 + 340) +
                        ": DataArray 'Points': the size header runs past the end of the data"));
  std::string far = raw;
  far.replace(far.find("offset=\"248\""), 12, "offset=\"99999\"");
  EXPECT_THAT(error_of(far), HasSubstr("DataArray 'gmsh:physical': offset '99999' is not within the"));
  std::string none = raw.substr(0, raw.find("<AppendedData")) + "</VTKFile>";
  EXPECT_THAT(error_of(none), HasSubstr("is appended but the file has no <AppendedData>"));
  std::string lz4 = raw;
  lz4.replace(lz4.find("header_type"), 0, "compressor=\"vtkLZ4DataCompressor\" ");
  EXPECT_THAT(error_of(lz4), HasSubstr("t.vtu: line 1: compressor 'vtkLZ4DataCompressor' not supported"));
  std::string enc = raw;
  enc.replace(enc.find("encoding=\"raw\""), 14, "encoding=\"hex\"");
  EXPECT_THAT(error_of(enc), HasSubstr("AppendedData encoding 'hex' not supported"));
}

TEST(IoVtuFormats, AsciiValuesMustFitTheirType) {
  const std::string head = R"(<VTKFile type="UnstructuredGrid"><UnstructuredGrid><Piece NumberOfPoints="4" NumberOfCells="1">
<Points><DataArray type="Float64" NumberOfComponents="3">0 0 0 1 0 0 0 1 0 0 0 1</DataArray></Points>
<Cells><DataArray type="Int64" Name="connectivity">0 1 2 3</DataArray>
<DataArray type="Int64" Name="offsets">4</DataArray>)";
  const std::string tail = "</Cells></Piece></UnstructuredGrid></VTKFile>";
  EXPECT_THAT(error_of(head + R"(<DataArray type="UInt8" Name="types">300</DataArray>)" + tail),
              HasSubstr("line 4: DataArray 'types': value out of range of UInt8 (300)"));
  EXPECT_THAT(error_of(head + R"(<DataArray type="UInt8" Name="types">-1</DataArray>)" + tail),
              HasSubstr("value out of range of UInt8 (-1)"));
  EXPECT_THAT(error_of(head + R"(<DataArray type="Float32" Name="types">10</DataArray>)" + tail),
              HasSubstr("DataArray 'types' must have an integer type (not Float32)"));
  EXPECT_THAT(error_of(head + R"(<DataArray type="UInt8" Name="types">10 x</DataArray>)" + tail),
              HasSubstr("line 4: DataArray 'types': not an integer (x)"));
  EXPECT_EQ(read_vtu(head + R"(<DataArray type="UInt8" Name="types">10</DataArray>)" + tail, "t").tets.size(), 1u);
}

}  // namespace
}  // namespace polydual
