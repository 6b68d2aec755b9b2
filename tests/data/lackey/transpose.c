/* A naive transpose of an N x N matrix of doubles: the column-wise writes miss where the
   row-wise reads hit, so a cache simulator must tell read misses from write misses. */
#define N 96
static double a[N][N], b[N][N];
int main(void) {
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) a[i][j] = i * N + j;
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) b[j][i] = a[i][j];
  return (int)b[N - 1][0];
}
