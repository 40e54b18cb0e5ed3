function dy = vanderpoldemo(t, y, mu)
%The seed's van der Pol oscillator: y1'' - mu (1 - y1^2) y1' + y1 = 0.
dy = [y(2); mu * (1 - y(1)^2) * y(2) - y(1)];
