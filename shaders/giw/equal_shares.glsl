// Positions along one piecewise-linear function so that each of the n - 1 intervals holds the
// same share of its weight (giw_warp.cpp's equalShares): the weights blended with the uniform
// share, integrated by trapezoids into cumulative[scratch ..], and inverted. The weights are
// importance[first ..] (a sketch row) or rowTotals[first ..] (the columns' distribution); the
// parameters go to rowX or columnT from `first`.
const int kRowOfImportance = 0, kRowTotals = 1;

float shareWeight(int source, int index) { return source == kRowOfImportance ? importance[index] : rowTotals[index]; }

void storeShare(int source, int index, float value) {
  if (source == kRowOfImportance) {
    rowX[index] = value;
  } else {
    columnT[index] = value;
  }
}

void equalShares(int source, int first, int n, int scratch) {
  float mean = 0.0;
  for (int i = 0; i < n; ++i) mean += shareWeight(source, first + i);
  mean /= float(n);
  float previous = shareWeight(source, first) * (1.0 - uUniformShare) + mean * uUniformShare;
  cumulative[scratch] = 0.0;
  for (int i = 1; i < n; ++i) {
    float w = shareWeight(source, first + i) * (1.0 - uUniformShare) + mean * uUniformShare;
    cumulative[scratch + i] = cumulative[scratch + i - 1] + 0.5 * (previous + w);
    previous = w;
  }
  float total = cumulative[scratch + n - 1];
  int segment = 0;
  for (int k = 0; k < n; ++k) {
    float target = total * float(k) / float(n - 1);
    while (segment < n - 2 && cumulative[scratch + segment + 1] < target) ++segment;
    float a = cumulative[scratch + segment], b = cumulative[scratch + segment + 1];
    float f = b > a ? clamp((target - a) / (b - a), 0.0, 1.0) : 0.0;
    float value = k == 0 ? 0.0 : (k == n - 1 ? float(n - 1) : float(segment) + f);
    storeShare(source, first + k, value);
  }
}
