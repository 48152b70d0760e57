# The plot of docs/model-validity.md (scripts/model-validity.sh passes `data` and `out`).
# Columns: cone turn roll report_err corrected_err residual residual_window slew_rel fault
set terminal pngcairo size 1100,450 font ",10"
set output out
set multiplot layout 1,2
set logscale y
set xlabel "body roll (rad/s)"
set grid
set key top left font ",8"
set format y "%.0e"
set title "Open loop over 1 s, body turn 1 rad/s"
set ylabel "worst gimbal-angle error (rad)"
plot for [c in "5 20"] data using ($2 == 1 && $1 == c ? $3 : 1/0):4 with linespoints title "report's model, cone ".c." deg", \
     for [c in "5 20"] data using ($2 == 1 && $1 == c ? $3 : 1/0):5 with linespoints dt 2 title "corrected model, cone ".c." deg"
set title "Component closed around the gimbal, body turn 1 rad/s"
set ylabel "worst residual (rad)"
plot for [c in "5 20"] data using ($2 == 1 && $1 == c ? $3 : 1/0):6 with linespoints title "from uncaging on, cone ".c." deg", \
     for [c in "5 20"] data using ($2 == 1 && $1 == c ? $3 : 1/0):7 with linespoints dt 2 title "steady slew, cone ".c." deg", \
     2e-4 with lines lc rgb "black" dt 3 title "2e-4 rad"
unset multiplot
