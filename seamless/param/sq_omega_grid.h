/* seamquad: quarter-turn arithmetic on the integer grid, shared by the
 * layout of Omega and its independent verifier (private header). */
#ifndef SQ_OMEGA_GRID_H
#define SQ_OMEGA_GRID_H

#include <stdint.h>

/* unit steps in directions 0..3 (counterclockwise from +x) */
static const int64_t DX[4] = {1, 0, -1, 0}, DY[4] = {0, 1, 0, -1};

/* (x, y) rotated by r quarter turns counterclockwise */
static inline void rot(uint32_t r, int64_t x, int64_t y, int64_t *ox, int64_t *oy)
{
    switch (r & 3u) {
    case 0: *ox = x, *oy = y; break;
    case 1: *ox = -y, *oy = x; break;
    case 2: *ox = -x, *oy = -y; break;
    default: *ox = y, *oy = -x; break;
    }
}

/* direction 0..3 of a unit axis vector, 4 otherwise */
static inline uint32_t dir_of(int64_t dx, int64_t dy)
{
    for (uint32_t d = 0; d < 4; d++)
        if (dx == DX[d] && dy == DY[d]) return d;
    return 4;
}

#endif
