/* SPDX-License-Identifier: BSD-3-Clause */
/* The nearest known name to a mistyped one, for "did you mean" messages (dynkit/lang.h):
 * the optimal string alignment distance (Damerau–Levenshtein with adjacent transpositions),
 * case folded. */
#include <ctype.h>
#include <string.h>

#include "dynkit/lang.h"

enum { NEAREST_MAX = 64 };

static int osa_distance(const char *a, const char *b)
{
    int la = (int)strlen(a), lb = (int)strlen(b);
    if (la > NEAREST_MAX || lb > NEAREST_MAX)
        return NEAREST_MAX + 1;
    int d[NEAREST_MAX + 1][NEAREST_MAX + 1];
    for (int i = 0; i <= la; i++)
        d[i][0] = i;
    for (int j = 0; j <= lb; j++)
        d[0][j] = j;
    for (int i = 1; i <= la; i++)
        for (int j = 1; j <= lb; j++) {
            const int ca = tolower((unsigned char)a[i - 1]), cb = tolower((unsigned char)b[j - 1]);
            int best = d[i - 1][j - 1] + (ca != cb);
            if (d[i - 1][j] + 1 < best)
                best = d[i - 1][j] + 1;
            if (d[i][j - 1] + 1 < best)
                best = d[i][j - 1] + 1;
            if (i > 1 && j > 1 && ca == tolower((unsigned char)b[j - 2]) &&
                tolower((unsigned char)a[i - 2]) == cb && d[i - 2][j - 2] + 1 < best)
                best = d[i - 2][j - 2] + 1;
            d[i][j] = best;
        }
    return d[la][lb];
}

const char *dyn_lang_nearest(const char *word, const char *const *names, int n)
{
    const char *best = NULL;
    int best_d = NEAREST_MAX + 1;
    if (!word)
        return NULL;
    for (int i = 0; i < n; i++) {
        if (!names[i])
            continue;
        const int dist = osa_distance(word, names[i]);
        if (dist < best_d) {
            best_d = dist;
            best = names[i];
        }
    }
    const int len = (int)strlen(word);
    const int limit = len / 3 > 1 ? len / 3 : 1;
    return best_d <= limit ? best : NULL;
}
