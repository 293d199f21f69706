// The appearance beside a mesh: its consistency check and texture sampling in linear light.
#include "meander/error.h"
#include "meander/textured_mesh.h"
#include "checker_quad.h"
#include "io_test_support.h"

#include <gtest/gtest.h>

#include <cmath>

namespace meander {
namespace {

using test::checker_quad;
using test::message_of;

double srgb_to_linear(double byte) {
  const double c = byte / 255;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

TEST(SampleTexture, TexelCentresGiveTheirColourInLinearLight) {
  const TexturedMesh quad = checker_quad();
  const Texture& t = quad.appearance.materials[0].texture;
  // The centre of the top-left texel: u = 1/4, v = 3/4 (v counts up from the bottom row).
  const LinearRgb red = sample_texture(t, {0.25f, 0.75f});
  EXPECT_NEAR(red[0], srgb_to_linear(220), 1e-6);
  EXPECT_NEAR(red[1], srgb_to_linear(30), 1e-6);
  const LinearRgb yellow = sample_texture(t, {0.75f, 0.25f});
  EXPECT_NEAR(yellow[0], srgb_to_linear(230), 1e-6);
  EXPECT_NEAR(yellow[2], srgb_to_linear(20), 1e-6);
}

TEST(SampleTexture, BlendsBetweenTexelsInLinearLightAndRepeats) {
  const TexturedMesh quad = checker_quad();
  const Texture& t = quad.appearance.materials[0].texture;
  // Half way between red (top left) and green (top right): the mean of linear values,
  // not of the sRGB bytes (which would be darker).
  const LinearRgb mid = sample_texture(t, {0.5f, 0.75f});
  EXPECT_NEAR(mid[0], (srgb_to_linear(220) + srgb_to_linear(30)) / 2, 1e-6);
  EXPECT_NEAR(mid[1], (srgb_to_linear(30) + srgb_to_linear(200)) / 2, 1e-6);
  // One period further is the same point.
  const LinearRgb again = sample_texture(t, {1.25f, -0.25f});
  const LinearRgb red = sample_texture(t, {0.25f, 0.75f});
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(again[k], red[k], 1e-6);
}

TEST(CheckAppearance, AcceptsTheCheckerQuadAndAPlainMesh) {
  const TexturedMesh quad = checker_quad();
  EXPECT_NO_THROW(check_appearance(quad.mesh, quad.appearance, "quad"));
  EXPECT_NO_THROW(check_appearance(quad.mesh, {}, "quad"));
}

TEST(CheckAppearance, RefusesWhatDoesNotFitTheMesh) {
  TexturedMesh quad = checker_quad();
  quad.appearance.texcoords.pop_back();
  EXPECT_EQ(message_of<UsageError>([&] { check_appearance(quad.mesh, quad.appearance, "quad"); }),
            "quad: 5 texture coordinates for 6 face corners");
  quad = checker_quad();
  quad.appearance.face_material = {0, 1};
  EXPECT_EQ(message_of<UsageError>([&] { check_appearance(quad.mesh, quad.appearance, "quad"); }),
            "quad: face 1: material 1 out of range (0..0)");
  quad = checker_quad();
  quad.appearance.texcoords.clear();
  EXPECT_EQ(message_of<UsageError>([&] { check_appearance(quad.mesh, quad.appearance, "quad"); }),
            "quad: a material has a texture but the mesh has no texture coordinates");
  quad = checker_quad();
  quad.appearance.materials[0].texture.rgba.pop_back();
  EXPECT_EQ(message_of<UsageError>([&] { check_appearance(quad.mesh, quad.appearance, "quad"); }),
            "quad: material 'checker': texture of 2x2 pixels has 15 bytes");
}

} // namespace
} // namespace meander
