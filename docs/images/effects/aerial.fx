# the CGAL aerial training scan without its class colours (shaded greys); classes ground 0,
# vegetation 1, roof 2; the unclassified rest (label 4294967295) stays with the root: toon greys
toon levels=6
node ground labels 0
clear
grade tint_r=0.95 tint_g=0.85 tint_b=0.6 recolour=1
watercolour
node vegetation labels 1
clear
grade tint_r=0.45 tint_g=0.8 tint_b=0.35 recolour=1 contrast=1.3
watercolour
node roofs labels 2
clear
grade tint_r=0.9 tint_g=0.45 tint_b=0.35 recolour=1
oil
