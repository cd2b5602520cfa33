# rastercmp chart; run: gnuplot -e "set terminal svg; set output 'x.svg'; DATA='bench_scaling_model.dat'" bench_scaling_model.gp
set key noenhanced
set linetype 1 lc rgb '#1f77b4' lw 3.5 dt 1 pt 7 ps 2
set linetype 2 lc rgb '#d62728' lw 3 dt 2 pt 5 ps 1.7
set linetype 3 lc rgb '#2ca02c' lw 2.5 dt 3 pt 9 ps 1.4
set linetype 4 lc rgb '#ff7f0e' lw 2 dt 4 pt 11 ps 1.1
set linetype 5 lc rgb '#9467bd' lw 3.5 dt 1 pt 13 ps 2
set linetype 6 lc rgb '#8c564b' lw 3 dt 2 pt 2 ps 1.7
set linetype 7 lc rgb '#e377c2' lw 2.5 dt 3 pt 3 ps 1.4
set linetype 8 lc rgb '#17becf' lw 2 dt 4 pt 1 ps 1.1
set linetype 9 lc rgb '#000000' lw 3.5 dt 1 pt 6 ps 2
set linetype 10 lc rgb '#bcbd22' lw 3 dt 2 pt 4 ps 1.7
set linetype 11 lc rgb '#7f7f7f' lw 2.5 dt 3 pt 8 ps 1.4
set linetype 12 lc rgb '#aec7e8' lw 2 dt 4 pt 10 ps 1.1
set linetype 13 lc rgb '#ff9896' lw 3.5 dt 1 pt 12 ps 2
set linetype 14 lc rgb '#98df8a' lw 3 dt 2 pt 14 ps 1.7
set linetype 15 lc rgb '#ffbb78' lw 2.5 dt 3 pt 7 ps 1.4
set linetype 16 lc rgb '#c5b0d5' lw 2 dt 4 pt 5 ps 1.1
set linetype cycle 16
set title 'fast path: projected speed-up on N cores (AMD EPYC)' noenhanced
set logscale xy 2
set xlabel 'workers N' noenhanced
set ylabel 'projected speed-up over 1 worker' noenhanced
set key outside right top
set grid
plot DATA index 0 using 1:2 title columnheader(3) with linespoints lw 2 pt 7, x title 'ideal' with lines dt 2 lc rgb 'gray'
