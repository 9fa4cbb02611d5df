# Prints a CSV file as an aligned table (what `column -s, -t` does, without
# util-linux's column, which a bare Debian system lacks).
# usage: awk -F, -f bench/csv_table.awk FILE.csv
{
  rows[NR] = $0
  if (NF > ncols) ncols = NF
  for (i = 1; i <= NF; ++i)
    if (length($i) > width[i]) width[i] = length($i)
}
END {
  for (r = 1; r <= NR; ++r) {
    n = split(rows[r], f, FS)
    line = ""
    for (i = 1; i <= n; ++i)
      line = line (i < n ? sprintf("%-" width[i] "s  ", f[i]) : f[i])
    print line
  }
}
