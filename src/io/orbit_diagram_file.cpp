#include "vibromap/io/orbit_diagram_file.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <span>

#include "attribute_seal.hpp"
#include "provenance.hpp"
#include "vibromap/io/hdf5_file.hpp"

namespace vibromap {

void write_orbit_diagram(const std::string& path, const OrbitDiagramData& data) {
  const std::size_t steps = data.axis.values.size();
  const auto keep = static_cast<std::size_t>(data.options.keep);
  write_hdf5_atomically(path, [&](Hdf5File& file) {
    Dataset param = file.write_dataset(data.axis.name, std::span<const double>(data.axis.values));
    param.make_dimension_scale(data.axis.name);
    param.set_attribute("units", data.axis.units);
    param.set_attribute("long_name", data.axis.long_name);
    param.set_attribute("key", data.axis.key);
    const std::vector<std::int8_t> directions{1, -1};
    Dataset direction = file.write_dataset("direction", std::span<const std::int8_t>(directions));
    direction.make_dimension_scale("direction");
    direction.set_attribute("long_name", "1: the key swept upwards, -1: downwards");
    std::vector<int> samples(keep);
    for (std::size_t k = 0; k < keep; ++k) samples[k] = static_cast<int>(k);
    Dataset sample = file.write_dataset("sample", std::span<const int>(samples));
    sample.make_dimension_scale("sample");
    sample.set_attribute("long_name", "stroboscopic state kept after the transient, in time order");

    const std::vector<const std::vector<DiagramStep>*> sides{&data.up, &data.down};
    std::vector<std::int8_t> status(2 * steps, 0);
    for (std::size_t d = 0; d < 2; ++d)
      for (std::size_t i = 0; i < steps; ++i) status[d * steps + i] = (*sides[d])[i].status == SolveStatus::ok ? 0 : 2;
    Dataset st = file.write_dataset("status", std::span<const std::int8_t>(status), {2, steps});
    st.attach_dimension_scale(direction, 0);
    st.attach_dimension_scale(param, 1);
    st.set_attribute("long_name", "0: ok, 2: the integration failed at this point");
    const char* names[] = {"x1", "x2", "v1", "v2"};
    const char* units[] = {"m", "m", "m/s", "m/s"};
    for (int c = 0; c < 4; ++c) {
      std::vector<double> values(2 * steps * keep, std::numeric_limits<double>::quiet_NaN());
      for (std::size_t d = 0; d < 2; ++d)
        for (std::size_t i = 0; i < steps; ++i) {
          const DiagramStep& s = (*sides[d])[i];
          for (std::size_t k = 0; k < s.strobe.size() && k < keep; ++k) values[(d * steps + i) * keep + k] = s.strobe[k][c];
        }
      Dataset x = file.write_dataset(names[c], std::span<const double>(values), {2, steps, keep});
      x.attach_dimension_scale(direction, 0);
      x.attach_dimension_scale(param, 1);
      x.attach_dimension_scale(sample, 2);
      x.set_attribute("units", units[c]);
      x.set_attribute("long_name", std::string(names[c]) + " at the period starts kept after the transient");
    }
    detail::set_provenance(file, "vibromap orbit diagram", data.scene_text, data.axis.key);
    file.set_attribute("transient", data.options.transient);
    file.set_attribute("keep", data.options.keep);
    detail::seal_attributes(file, kOrbitDiagramFormat);  // last: the format version, then the seal over every attribute (attribute_seal.hpp)
  });
}

}  // namespace vibromap
