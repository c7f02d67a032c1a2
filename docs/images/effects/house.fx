# the generated house scene: 1 ground, 2 wall, 3 roof, 4 trunk, 5 crown, 6 sphere
toon
node ground labels 1
clear
grade saturation=0.6 brightness=0.1
watercolour
node trees labels 4 5
clear
watercolour
node roof labels 3
oil
