// Test helper for the shell end-to-end tests: prints the mean R G B of a box of a PNG, centred at
// (fx, fy) given as fractions of the width and height. Exit 2 on bad usage or an unreadable file.
#include <stb/stb_image.h>

#include <cstdio>
#include <cstdlib>

int main(int argc, char** argv) {
    if (argc != 5) {
        std::fprintf(stderr, "usage: png_probe FILE.png FX FY HALF_SIZE\n");
        return 2;
    }
    int w = 0, h = 0, n = 0;
    unsigned char* px = stbi_load(argv[1], &w, &h, &n, 3);
    if (!px) {
        std::fprintf(stderr, "png_probe: cannot read %s\n", argv[1]);
        return 2;
    }
    const int cx = static_cast<int>(std::atof(argv[2]) * w), cy = static_cast<int>(std::atof(argv[3]) * h);
    const int r = std::atoi(argv[4]);
    double sum[3] = {0, 0, 0};
    int count = 0;
    for (int y = cy - r; y <= cy + r; ++y) {
        for (int x = cx - r; x <= cx + r; ++x) {
            if (x < 0 || y < 0 || x >= w || y >= h) continue;
            for (int c = 0; c < 3; ++c) sum[c] += px[(y * w + x) * 3 + c];
            ++count;
        }
    }
    stbi_image_free(px);
    std::printf("%d %d %d\n", static_cast<int>(sum[0] / count), static_cast<int>(sum[1] / count),
                static_cast<int>(sum[2] / count));
    return 0;
}
