// SPDX-License-Identifier: BSD-3-Clause
// Liquids by name (core/fluids.hpp, data/fluids.csv): the correlations against published values, and the scene's
// [fluid] keys (fluid, mass_fraction, temperature, inline overrides, the errors).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/errors.hpp"
#include "core/fluids.hpp"
#include "core/materials.hpp"
#include "core/scene.hpp"
#include "run/simulate.hpp"
#include "run/summary.hpp"
#include "tests/input_error.hpp"
#include "tests/scene_text.hpp"

using namespace imcol;
namespace fc = imcol::fluid_correlations;

namespace {

/// The basic wall scene with `fluid_table` as its [fluid] table.
std::string with_fluid(const std::string& fluid_table) {
  return test::edit(test::basic_wall_scene(), test::fluid(0.01), fluid_table);
}

/// The input error parsing `text` gives; "" if none.
std::string error_of(const std::string& text, const std::vector<Override>& ov = {}) {
  return test::input_error_of([&] { parse_scene(text, "f.toml", ov); });
}

}  // namespace

// IAPWS R12-08 (2008), Table 4 (verification values): T = 298.15 K, rho = 998 kg/m^3 -> mu = 889.735100 uPa s.
TEST(Fluids, IapwsViscosityCheckValue) {
  EXPECT_NEAR(fc::water_viscosity_iapws(25.0, 998.0), 889.735100e-6, 1e-12);
}

// Pure water at 20 °C: 998.2 kg/m^3 (Kell 1975; Tanaka et al. 2001, Metrologia 38:301, give 998.207) and
// 1.002 mPa s (CRC Handbook; the NBS standard value 1.0020 mPa s at 20 °C).
TEST(Fluids, WaterAt20C) {
  const double rho = fc::water_density_kell(20.0);
  EXPECT_NEAR(rho, 998.207, 0.01);
  EXPECT_NEAR(fc::water_viscosity_iapws(20.0, rho), 1.002e-3, 0.001e-3);
  const FluidEntry* w = FluidTable::builtin().find("water");
  ASSERT_NE(w, nullptr);
  EXPECT_DOUBLE_EQ(w->viscosity.at(0, 20.0), fc::water_viscosity_iapws(20.0, rho));
}

// Cheng (2008), Ind. Eng. Chem. Res. 47:3285, compares his formula with the data of Segur & Oberstar (1951), as in
// the Dow glycerine tables (mPa s): 50 wt% at 20 °C 6.00; 80 wt% at 20 °C 60.1; 80 wt% at 40 °C 20.8;
// 100 wt% at 20 °C 1410; 0 wt% at 20 °C 1.005.
TEST(Fluids, ChengViscosityAgainstTables) {
  struct Point { double w, t, mu_mPas; };
  for (const Point& p : {Point{0.5, 20, 6.00}, Point{0.8, 20, 60.1}, Point{0.8, 40, 20.8}, Point{1.0, 20, 1410}, Point{0.0, 20, 1.005}})
    EXPECT_NEAR(fc::glycerol_water_viscosity_cheng(p.w, p.t) / (p.mu_mPas * 1e-3), 1.0, 0.05) << p.w << " at " << p.t << " °C";
  EXPECT_NEAR(fc::glycerol_water_viscosity_cheng(0.5, 20) * 1e3, 6.0, 0.05);  // the same table value to 1 %
}

// Volk & Kähler (2018), Exp. Fluids 59:75, against the glycerine producers' density tables (Dow; g/cm^3):
// 50 wt% 1.1263 at 20 °C, 1.1211 at 30 °C; 80 wt% 1.2085 at 20 °C; 100 wt% 1.26108 at 20 °C; 0 wt% 0.99823 at 20 °C.
TEST(Fluids, VolkDensityAgainstTables) {
  struct Point { double w, t, rho; };
  for (const Point& p : {Point{0.5, 20, 1126.3}, Point{0.5, 30, 1121.1}, Point{0.8, 20, 1208.5}, Point{1.0, 20, 1261.08},
                         Point{0.0, 20, 998.23}})
    EXPECT_NEAR(fc::glycerol_water_density_volk(p.w, p.t), p.rho, 0.002 * p.rho) << p.w << " at " << p.t << " °C";
}

TEST(Fluids, TableHasTheShippedExperimentLiquids) {
  const auto& t = FluidTable::builtin();
  for (const char* name : {"water", "glycerol-water", "gondret-oil-100mPas", "gondret-oil-20mPas", "gondret-oil-10mPas",
                           "gondret-oil-5mPas", "li2010-4.1cP", "li2010-43cP", "li2010-gg3462"}) {
    const FluidEntry* e = t.find(name);
    ASSERT_NE(e, nullptr) << name;
    EXPECT_FALSE(e->density.source.empty()) << name;
    EXPECT_FALSE(e->viscosity.source.empty()) << name;
  }
  // The experiment liquids hold the values the shipped scenes of those experiments use.
  struct Use { const char* fluid; const char* scene; };
  for (const Use& u : {Use{"gondret-oil-100mPas", "gondret/st27"}, Use{"gondret-oil-20mPas", "gondret/st100"},
                       Use{"gondret-oil-20mPas", "gondret/st192"}, Use{"gondret-oil-10mPas", "gondret/st152"},
                       Use{"gondret-oil-5mPas", "gondret/st742"}, Use{"li2010-4.1cP", "seed_run1"}, Use{"li2010-43cP", "seed_run4"},
                       Use{"li2010-gg3462", "gg3462"}}) {
    const Scene sc = load_scene(data_dir() + "/scenes/" + u.scene + ".toml");
    const FluidEntry* e = t.find(u.fluid);
    EXPECT_DOUBLE_EQ(*e->density.value, sc.fluid->density) << u.scene;
    EXPECT_DOUBLE_EQ(*e->viscosity.value, sc.fluid->viscosity) << u.scene;
  }
}

TEST(Fluids, SceneNamesGlycerolWater) {
  const Scene sc = parse_scene(with_fluid("[fluid]\nfluid = \"glycerol-water\"\nmass_fraction = 0.5\ntemperature = 20.0\n"), "f.toml");
  ASSERT_TRUE(sc.fluid);
  EXPECT_EQ(sc.fluid->name, "glycerol-water");
  EXPECT_DOUBLE_EQ(sc.fluid->density, fc::glycerol_water_density_volk(0.5, 20));
  EXPECT_DOUBLE_EQ(sc.fluid->viscosity, fc::glycerol_water_viscosity_cheng(0.5, 20));
  EXPECT_NE(sc.fluid->density_source.find("Volk"), std::string::npos);
  EXPECT_NE(sc.fluid->viscosity_source.find("Cheng"), std::string::npos);
  // --set reaches the new keys.
  const Scene more = parse_scene(with_fluid("[fluid]\nfluid = \"glycerol-water\"\nmass_fraction = 0.5\n"), "f.toml",
                                 {{"fluid.mass_fraction", "0.6"}});
  EXPECT_DOUBLE_EQ(more.fluid->viscosity, fc::glycerol_water_viscosity_cheng(0.6, 20));
  EXPECT_DOUBLE_EQ(*more.fluid->temperature, 20.0);  // the default temperature
}

TEST(Fluids, InlineValueOverridesTheTable) {
  const Scene sc = parse_scene(with_fluid("[fluid]\nfluid = \"water\"\ntemperature = 25.0\nviscosity = 0.002\n"), "f.toml");
  EXPECT_DOUBLE_EQ(sc.fluid->viscosity, 0.002);
  EXPECT_EQ(sc.fluid->viscosity_source, "scene");
  EXPECT_DOUBLE_EQ(sc.fluid->density, fc::water_density_kell(25.0));
  EXPECT_NE(sc.fluid->density_source.find("Kell"), std::string::npos);
  // Inline only: as before, both values from the scene.
  const Scene plain = parse_scene(test::basic_wall_scene(), "f.toml");
  EXPECT_EQ(plain.fluid->name, "");
  EXPECT_EQ(plain.fluid->density_source, "scene");
}

TEST(Fluids, BadFluidKeysAreRefused) {
  // Out of the correlation's range: the key, the value and the range.
  std::string e = error_of(with_fluid("[fluid]\nfluid = \"glycerol-water\"\nmass_fraction = 0.5\ntemperature = 40.0\n"));
  EXPECT_NE(e.find("key 'fluid.temperature'"), std::string::npos) << e;
  EXPECT_NE(e.find("40"), std::string::npos) << e;
  EXPECT_NE(e.find("[15, 30]"), std::string::npos) << e;
  e = error_of(with_fluid("[fluid]\nfluid = \"glycerol-water\"\nmass_fraction = 1.2\n"));
  EXPECT_NE(e.find("key 'fluid.mass_fraction'"), std::string::npos) << e;
  EXPECT_NE(e.find("1.2"), std::string::npos) << e;
  // Unknown fluid: the known ones listed.
  e = error_of(with_fluid("[fluid]\nfluid = \"honey\"\n"));
  EXPECT_NE(e.find("key 'fluid.fluid'"), std::string::npos) << e;
  EXPECT_NE(e.find("glycerol-water"), std::string::npos) << e;
  EXPECT_NE(e.find("gondret-oil-20mPas"), std::string::npos) << e;
  // A key of another fluid.
  e = error_of(with_fluid("[fluid]\nfluid = \"water\"\nmass_fraction = 0.5\n"));
  EXPECT_NE(e.find("key 'fluid.mass_fraction'"), std::string::npos) << e;
  e = error_of(with_fluid("[fluid]\ndensity = 1000.0\nviscosity = 0.001\nmass_fraction = 0.5\n"));
  EXPECT_NE(e.find("key 'fluid.mass_fraction'"), std::string::npos) << e;
  e = error_of(with_fluid("[fluid]\nfluid = \"gondret-oil-20mPas\"\ntemperature = 25.0\n"));
  EXPECT_NE(e.find("key 'fluid.temperature'"), std::string::npos) << e;
  e = error_of(with_fluid("[fluid]\nfluid = \"glycerol-water\"\n"));
  EXPECT_NE(e.find("key 'fluid.mass_fraction'"), std::string::npos) << e;
  EXPECT_NE(e.find("missing"), std::string::npos) << e;
  // With the density inline, only the viscosity correlation's range applies (Cheng: 0-100 °C).
  EXPECT_EQ(error_of(with_fluid("[fluid]\nfluid = \"glycerol-water\"\nmass_fraction = 0.5\ntemperature = 40.0\ndensity = 1115.0\n")), "");
}

TEST(Fluids, SummaryRecordsTheValuesAndSources) {
  const RunResult r = simulate(load_scene(data_dir() + "/scenes/glass_steel_glycerol50.toml"));
  const auto& f = r.summary_json.at("fluid");
  EXPECT_EQ(f.at("name"), "glycerol-water");
  EXPECT_DOUBLE_EQ(f.at("mass_fraction").get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(f.at("temperature_C").get<double>(), 20.0);
  EXPECT_NEAR(f.at("density_kg_m3").get<double>(), 1126, 1.0);
  EXPECT_NEAR(f.at("viscosity_Pa_s").get<double>(), 6.0e-3, 0.05e-3);
  EXPECT_NE(f.at("viscosity_source").get<std::string>().find("Cheng"), std::string::npos);
  const std::string text = human_summary(r);
  EXPECT_NE(text.find("fluid: glycerol-water, w = 0.5, 20 °C"), std::string::npos) << text;
  // A real bounce.
  ASSERT_TRUE(r.summary.e);
  EXPECT_GT(*r.summary.e, 0.05);
  EXPECT_LT(*r.summary.e, 0.97);
}

// The run's line names each value's source up to its year; a source without a year in parentheses, whole.
TEST(Fluids, FluidLineNamesEverySource) {
  FluidSpec f;
  f.name = "castor-oil";
  f.density = 961;
  f.viscosity = 0.985;
  f.density_source = "CRC Handbook of Chemistry and Physics";
  f.viscosity_source = "Cheng (2008) Ind. Eng. Chem. Res. 47:3285";
  const std::string line = run::fluid_line(f);
  EXPECT_NE(line.find("(CRC Handbook of Chemistry and Physics)"), std::string::npos) << line;
  EXPECT_NE(line.find("(Cheng (2008))"), std::string::npos) << line;
  f.viscosity_source = "scene";
  EXPECT_NE(run::fluid_line(f).find("Pa s (inline)"), std::string::npos) << run::fluid_line(f);
}

// The material and fluid tables read their numbers alike: an empty optional cell is absent; text, "nan" or "inf" is
// refused naming the file, line and column.
TEST(Fluids, TablesRefuseCellsThatAreNotFiniteNumbers) {
  const std::filesystem::path csv = std::filesystem::temp_directory_path() / ("imcol_tables_" + std::to_string(::getpid()) + ".csv");
  auto error_loading = [&](auto load, const std::string& text) {
    std::ofstream(csv) << text;
    return test::input_error_of([&] { load(csv.string()); });
  };
  const std::string materials = "# comment\nmaterial,density_kg_m3,youngs_modulus_Pa,poisson_ratio,e_dry,roughness_m\n";
  auto material = [](const std::string& p) { MaterialTable::load(p); };
  EXPECT_EQ(error_loading(material, materials + "glass,2500,6e10,0.23,,\n"), "");
  for (const char* density : {"nan", "inf", "25x0", ""}) {
    const std::string e = error_loading(material, materials + "glass," + density + ",6e10,0.23,,\n");
    EXPECT_NE(e.find(csv.string() + ":3"), std::string::npos) << density << ": " << e;
    EXPECT_NE(e.find("key 'density_kg_m3'"), std::string::npos) << density << ": " << e;
  }
  EXPECT_NE(error_loading(material, materials + "glass,2500,6e10,0.23,-inf,\n").find("key 'e_dry'"), std::string::npos);
  const std::string fluids = "fluid,property,value,correlation,t_min_C,t_max_C,w_min,w_max,source\n";
  auto fluid = [](const std::string& p) { FluidTable::load(p); };
  EXPECT_EQ(error_loading(fluid, fluids + "oil,density,950,,,,,,a book\noil,viscosity,0.02,,,,,,a book\n"), "");
  for (const char* value : {"nan", "inf", "0.0x2"}) {
    const std::string e = error_loading(fluid, fluids + "oil,density,950,,,,,,a book\noil,viscosity," + value + ",,,,,,a book\n");
    EXPECT_NE(e.find(csv.string() + ":3"), std::string::npos) << value << ": " << e;
    EXPECT_NE(e.find("key 'value'"), std::string::npos) << value << ": " << e;
  }
  std::filesystem::remove(csv);
}
