// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Axial cell counts the kernel's sine transforms take fast. The DST-I of a line is an FFT of length nz (and nz/2);
// FFTW's cost per point grows with the largest prime factor of the length (a factor 29 made a step ~3× slower than
// a nearby 7-smooth length), so a grid sized from a physical extent is rounded up to a 7-smooth count.
namespace imcol::flow {

/// The smallest count ≥ n that is a multiple of `multiple` and has no prime factor above 7.
int fft_friendly_cells(int n, int multiple);

}  // namespace imcol::flow
