set terminal pngcairo size 800,500 font 'sans,11'
set output 'docs/plots/whitted.png'
set title 'Scene "whitted": render time against recursion depth (640x480, 5 spp)'
set xlabel 'recursion depth'
set ylabel 'seconds'
set key top left
set grid
set xtics 1
plot 'docs/plots/whitted.dat' using 1:2 with linespoints lw 2 title 'scalar-float', 'docs/plots/whitted.dat' using 1:3 with linespoints lw 2 title 'scalar-double', 'docs/plots/whitted.dat' using 1:4 with linespoints lw 2 title 'sse', 'docs/plots/whitted.dat' using 1:5 with linespoints lw 2 title 'avx2', 'docs/plots/whitted.dat' using 1:6 with linespoints lw 2 title 'avx512', 'docs/plots/whitted.dat' using 1:7 with linespoints lw 2 title 'stream-sse', 'docs/plots/whitted.dat' using 1:8 with linespoints lw 2 title 'stream-avx2', 'docs/plots/whitted.dat' using 1:9 with linespoints lw 2 title 'stream-avx512'
