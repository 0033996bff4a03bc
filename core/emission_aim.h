#pragma once
// Where a light's photons are aimed: a grid of cells over two of the uniforms a photon is drawn
// from (a sun: where on its rectangle it starts; a point, spot or quad light: which way it
// leaves), each cell drawn with its own probability and the photon's flux divided by it
// (relative to a uniform draw), so the estimate stays unbiased. Most of a sun's photons, or of
// a lamp's outside a window, may land where no camera looks (a roof, the outside of a wall): a
// pilot (stages/render/emission_aim_pilot.h) counts, cell by cell, the records its photons leave
// where the camera sees, and the table draws the cells in proportion to that, with a share for
// every cell so that no light is left out. An empty table draws the uniforms as they are.
#include <cstddef>
#include <vector>

namespace sl {

class EmissionAim {
public:
    EmissionAim() = default;
    // `usefulness`: n x n values (row-major: the row is the second uniform's cell), >= 0;
    // `floor`: the share of the draws spread evenly over all cells (0 < floor <= 1). All zero:
    // an empty table.
    EmissionAim(int n, const std::vector<double>& usefulness, double floor);

    bool empty() const { return n_ == 0; }
    int cells() const { return n_; }
    // Maps two uniforms to two others (in [0, 1)) and returns the flux factor:
    // (1 / cells) / the drawn cell's probability. Rows by their marginal, then a column within
    // the row, so that stratified uniforms stay stratified.
    float draw(float u1, float u2, float& x, float& y) const;
    // The probability of cell (column i, row j), for tests.
    double probability(int i, int j) const { return prob_[static_cast<size_t>(j) * n_ + i]; }

private:
    int n_ = 0;
    std::vector<double> prob_;    // per cell
    std::vector<float> row_cdf_;  // n + 1: the rows' marginal
    std::vector<float> col_cdf_;  // n x (n + 1): within each row
};

}  // namespace sl
